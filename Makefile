# sph: incompressible SPH for viscoplastic flows (C11, Lua 5.4, Cairo)
CC      ?= cc
PKGS    := lua5.4 cairo
PKG_CFLAGS := $(shell pkg-config --cflags $(PKGS))
PKG_LIBS   := $(shell pkg-config --libs $(PKGS))
CAIRO_LIBS := $(shell pkg-config --libs cairo)
# the version (src/sph.h) and the shared library's soname: libsph.so.MAJOR
VERSION := $(shell sed -n 's/.*define SPH_VERSION "\(.*\)".*/\1/p' src/sph.h)
SOMAJOR := $(firstword $(subst ., ,$(VERSION)))
SONAME  := libsph.so.$(SOMAJOR)
WARN    := -Wall -Wextra -Wshadow -Wstrict-prototypes -Wmissing-prototypes \
           -Wmissing-declarations -Wundef -Wpointer-arith -Wwrite-strings -Wno-unknown-pragmas
OPT     ?= -O2 -march=x86-64-v2
CFLAGS  += -std=c11 -D_POSIX_C_SOURCE=200809L $(OPT) -g -fopenmp -fno-math-errno -fno-trapping-math -fPIC $(WARN) $(PKG_CFLAGS) \
           -DSPH_LUA_DIR='"$(abspath lua)"'
LDLIBS  += $(PKG_LIBS) -lm -fopenmp
ifeq ($(SANITIZE),1)
  B       := build-san
  CFLAGS  += -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
  LDFLAGS += -fsanitize=address,undefined
  SO_DEFS :=
else
  B       := build
  SO_DEFS := -Wl,-z,defs
endif

ENGINE_SRC := $(filter-out src/main.c src/l%.c,$(wildcard src/*.c))
BIND_SRC   := $(wildcard src/l*.c)
ENGINE_OBJ := $(ENGINE_SRC:src/%.c=$(B)/%.o)
BIND_OBJ   := $(BIND_SRC:src/%.c=$(B)/%.o)
UNIT_SRC   := $(wildcard tests/unit/test_*.c)
UNIT_BIN   := $(UNIT_SRC:tests/unit/%.c=$(B)/tests/%)
EXAMPLE_BIN := $(patsubst examples/%.c,$(B)/examples/%,$(wildcard examples/*.c))

all: $(B)/sph $(B)/libsph.a $(B)/libsph.so $(B)/sph.so $(UNIT_BIN) $(EXAMPLE_BIN)

$(B)/%.o: src/%.c | $(B)
	$(CC) $(CFLAGS) -MMD -MP -c $< -o $@

$(B)/libsph.a: $(ENGINE_OBJ)
	$(AR) rcs $@ $^

# the engine and the pictures as a shared library: libsph.so.VERSION, soname libsph.so.MAJOR,
# needing cairo, libm and OpenMP's runtime (-z defs: nothing left undefined)
$(B)/libsph.so.$(VERSION): $(ENGINE_OBJ)
	$(CC) $(LDFLAGS) -shared -Wl,-soname,$(SONAME) $(SO_DEFS) -o $@ $^ $(CAIRO_LIBS) -lm -fopenmp

$(B)/libsph.so: $(B)/libsph.so.$(VERSION)
	ln -sf libsph.so.$(VERSION) $(B)/$(SONAME)
	ln -sf libsph.so.$(VERSION) $@

$(B)/sph: $(B)/main.o $(BIND_OBJ) $(B)/libsph.a
	$(CC) $(LDFLAGS) -o $@ $(B)/main.o $(BIND_OBJ) $(B)/libsph.a $(LDLIBS) -Wl,-E

$(B)/sph.so: $(BIND_OBJ) $(B)/libsph.a
	$(CC) $(LDFLAGS) -shared -o $@ $(BIND_OBJ) $(B)/libsph.a $(filter-out -llua5.4,$(LDLIBS))

$(B)/tests/%: tests/unit/%.c tests/unit/unit.h $(B)/libsph.a | $(B)
	@mkdir -p $(B)/tests
	$(CC) $(CFLAGS) -Isrc -o $@ $< $(B)/libsph.a $(LDFLAGS) $(LDLIBS)

# the C examples (examples/squeeze.c), against the tree's headers and libsph.a; the smoke
# test tests/lua/test_examples.lua runs them
$(B)/examples/%: examples/%.c $(B)/libsph.a | $(B)
	@mkdir -p $(B)/examples
	$(CC) $(CFLAGS) -Isrc -o $@ $< $(B)/libsph.a $(LDFLAGS) $(LDLIBS)

$(B):
	mkdir -p $(B)

test: all
	@CC="$(CC)" bash tests/run.sh $(B)

# the suite under the sanitizers; the API fuzz test (tests/lua/test_fuzz.lua) makes 30,000
# calls there, with the seed SPH_FUZZ_SEED from the environment (else the clock's; printed)
check:
	$(MAKE) SANITIZE=1 OPT=-O1 all
	ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 SPH_FUZZ_CALLS=$${SPH_FUZZ_CALLS:-30000} \
	    SPH_FUZZ_SEED=$${SPH_FUZZ_SEED:-$$(date +%s)} CC="$(CC)" bash tests/run.sh build-san

# make bench [only=WORD,...|none] [quick=1]: see scripts/bench.sh
bench: all $(B)/bench_render
	@sh scripts/bench.sh $(B) $(if $(only),only=$(only)) $(if $(quick),quick=$(quick))

# the renderer benchmark (not a test, not built by `all`)
$(B)/bench_render: tests/bench/bench_render.c $(B)/libsph.a | $(B)
	$(CC) $(CFLAGS) -Isrc -o $@ $< $(B)/libsph.a $(LDFLAGS) $(LDLIBS)

stability: all
	$(B)/sph scripts/stability.lua

# the reference cases of ../shared/REFERENCES.md sections 1-4 at up to three resolutions:
# docs/validation.md and docs/validation_*.png (about 17 minutes on two cores: two sections at a
# time, each world on one thread; jobs=1 for one process, threads=2 for two threads a world)
validate: all
	$(B)/sph scripts/validate.lua $(if $(threads),threads=$(threads)) $(if $(jobs),jobs=$(jobs))

# the seed paper's Figures 3-7 (../shared/paper), next to the references of
# ../shared/REFERENCES.md: docs/paper.md and docs/paper/fig3.png ... fig7.png (the Figure 5
# grid and its animations). make paper: dx = 1/20 and 1/40 (about 11 minutes on one thread);
# make paper quick=1: dx = 1/20, shorter runs (about a minute).
# n=20,40 and threads=1 pass through (scripts/paper.lua says the rest).
paper: all
	$(B)/sph scripts/paper.lua $(if $(quick),quick=$(quick)) $(if $(n),n=$(n)) $(if $(threads),threads=$(threads))

# The headers a C user needs: sph.h (the engine, C library only) and sph_pictures.h (render,
# plot, animate; plain data in, PNG out: link with cairo). pictures_cairo.h is internal.
PUBLIC_HEADERS := src/sph.h src/sph_pictures.h
# make install [PREFIX=/usr/local] [DESTDIR=]: the library (headers, libsph.a, libsph.so,
# sph.pc), the Lua module where a stock lua5.4 looks under PREFIX (lib/lua/5.4/sph.so,
# share/lua/5.4/sph/*.lua), the host (bin/sph: it finds the helpers at ../share/lua/5.4 from
# its own path, src/main.c), the scripts and examples (share/sph) and the docs
# (share/doc/sph). make uninstall removes those files (the same lists: run it from the same
# source tree) and the folders that are sph's own, when empty.
PREFIX  ?= /usr/local
DESTDIR ?=
bindir       := $(PREFIX)/bin
libdir       := $(PREFIX)/lib
includedir   := $(PREFIX)/include
pkgconfigdir := $(libdir)/pkgconfig
luacdir      := $(libdir)/lua/5.4
luadir       := $(PREFIX)/share/lua/5.4
sharedir     := $(PREFIX)/share/sph
docdir       := $(PREFIX)/share/doc/sph
LUA_FILES      := $(wildcard lua/sph/*.lua)
SCRIPT_FILES   := $(wildcard scripts/*.lua)
EXAMPLE_FILES  := $(wildcard examples/*.lua examples/*.c examples/README.md)
DOC_FILES      := $(wildcard docs/*.md docs/*.png)
PAPER_FILES    := $(wildcard docs/paper/*.png)
D := $(DESTDIR)
install: all
	install -d $(D)$(bindir) $(D)$(libdir) $(D)$(includedir) $(D)$(pkgconfigdir) $(D)$(luacdir) \
	    $(D)$(luadir)/sph $(D)$(sharedir)/scripts $(D)$(sharedir)/examples $(D)$(docdir)/docs
	install -m 755 $(B)/sph $(D)$(bindir)/sph
	install -m 644 $(PUBLIC_HEADERS) $(D)$(includedir)/
	install -m 644 $(B)/libsph.a $(D)$(libdir)/libsph.a
	install -m 755 $(B)/libsph.so.$(VERSION) $(D)$(libdir)/libsph.so.$(VERSION)
	ln -sf libsph.so.$(VERSION) $(D)$(libdir)/$(SONAME)
	ln -sf libsph.so.$(VERSION) $(D)$(libdir)/libsph.so
	printf '%s\n' 'prefix=$(PREFIX)' 'libdir=$(libdir)' 'includedir=$(includedir)' '' \
	    'Name: sph' 'Description: incompressible SPH for viscoplastic flows (engine and pictures)' \
	    'Version: $(VERSION)' 'Requires.private: cairo' 'Cflags: -I$${includedir}' \
	    'Libs: -L$${libdir} -lsph' 'Libs.private: -lm -fopenmp' >$(D)$(pkgconfigdir)/sph.pc
	chmod 644 $(D)$(pkgconfigdir)/sph.pc
	install -m 755 $(B)/sph.so $(D)$(luacdir)/sph.so
	install -m 644 $(LUA_FILES) $(D)$(luadir)/sph/
	install -m 644 $(SCRIPT_FILES) $(D)$(sharedir)/scripts/
	$(if $(EXAMPLE_FILES),install -m 644 $(EXAMPLE_FILES) $(D)$(sharedir)/examples/)
	install -m 644 README.md $(D)$(docdir)/README.md
	install -m 644 $(DOC_FILES) $(D)$(docdir)/docs/
	$(if $(PAPER_FILES),install -d $(D)$(docdir)/docs/paper && install -m 644 $(PAPER_FILES) $(D)$(docdir)/docs/paper/)

uninstall:
	rm -f $(D)$(bindir)/sph $(addprefix $(D)$(includedir)/,$(notdir $(PUBLIC_HEADERS))) \
	    $(D)$(libdir)/libsph.a $(D)$(libdir)/libsph.so.$(VERSION) $(D)$(libdir)/$(SONAME) \
	    $(D)$(libdir)/libsph.so $(D)$(pkgconfigdir)/sph.pc $(D)$(luacdir)/sph.so
	rm -f $(addprefix $(D)$(luadir)/sph/,$(notdir $(LUA_FILES)))
	rm -f $(addprefix $(D)$(sharedir)/scripts/,$(notdir $(SCRIPT_FILES)))
	rm -f $(addprefix $(D)$(sharedir)/examples/,$(notdir $(EXAMPLE_FILES)))
	rm -f $(D)$(docdir)/README.md $(addprefix $(D)$(docdir)/docs/,$(notdir $(DOC_FILES)))
	rm -f $(addprefix $(D)$(docdir)/docs/paper/,$(notdir $(PAPER_FILES)))
	for d in $(D)$(luadir)/sph $(D)$(sharedir)/scripts $(D)$(sharedir)/examples $(D)$(sharedir) \
	         $(D)$(docdir)/docs/paper $(D)$(docdir)/docs $(D)$(docdir); do [ ! -d "$$d" ] || rmdir "$$d" 2>/dev/null || true; done

clean:
	rm -rf build build-san

.PHONY: all test check bench stability validate paper install uninstall clean
-include $(wildcard $(B)/*.d)
