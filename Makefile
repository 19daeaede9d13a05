# sph: incompressible SPH for viscoplastic flows (C11, Lua 5.4, Cairo)
CC      ?= cc
PKGS    := lua5.4 cairo
PKG_CFLAGS := $(shell pkg-config --cflags $(PKGS))
PKG_LIBS   := $(shell pkg-config --libs $(PKGS))
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
else
  B       := build
endif

ENGINE_SRC := $(filter-out src/main.c src/l%.c,$(wildcard src/*.c))
BIND_SRC   := $(wildcard src/l*.c)
ENGINE_OBJ := $(ENGINE_SRC:src/%.c=$(B)/%.o)
BIND_OBJ   := $(BIND_SRC:src/%.c=$(B)/%.o)
UNIT_SRC   := $(wildcard tests/unit/test_*.c)
UNIT_BIN   := $(UNIT_SRC:tests/unit/%.c=$(B)/tests/%)

all: $(B)/sph $(B)/libsph.a $(B)/sph.so $(UNIT_BIN)

$(B)/%.o: src/%.c | $(B)
	$(CC) $(CFLAGS) -MMD -MP -c $< -o $@

$(B)/libsph.a: $(ENGINE_OBJ)
	$(AR) rcs $@ $^

$(B)/sph: $(B)/main.o $(BIND_OBJ) $(B)/libsph.a
	$(CC) $(LDFLAGS) -o $@ $(B)/main.o $(BIND_OBJ) $(B)/libsph.a $(LDLIBS) -Wl,-E

$(B)/sph.so: $(BIND_OBJ) $(B)/libsph.a
	$(CC) $(LDFLAGS) -shared -o $@ $(BIND_OBJ) $(B)/libsph.a $(filter-out -llua5.4,$(LDLIBS))

$(B)/tests/%: tests/unit/%.c tests/unit/unit.h $(B)/libsph.a | $(B)
	@mkdir -p $(B)/tests
	$(CC) $(CFLAGS) -Isrc -o $@ $< $(B)/libsph.a $(LDFLAGS) $(LDLIBS)

$(B):
	mkdir -p $(B)

test: all
	@sh tests/run.sh $(B)

# the suite under the sanitizers; the API fuzz test (tests/lua/test_fuzz.lua) makes 30,000
# calls there, with the seed SPH_FUZZ_SEED from the environment (else the clock's; printed)
check:
	$(MAKE) SANITIZE=1 OPT=-O1 all
	ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 SPH_FUZZ_CALLS=$${SPH_FUZZ_CALLS:-30000} \
	    SPH_FUZZ_SEED=$${SPH_FUZZ_SEED:-$$(date +%s)} sh tests/run.sh build-san

# make bench [only=WORD,...|none] [quick=1]: see scripts/bench.sh
bench: all $(B)/bench_render
	@sh scripts/bench.sh $(B) $(if $(only),only=$(only)) $(if $(quick),quick=$(quick))

# the renderer benchmark (not a test, not built by `all`)
$(B)/bench_render: tests/bench/bench_render.c $(B)/libsph.a | $(B)
	$(CC) $(CFLAGS) -Isrc -o $@ $< $(B)/libsph.a $(LDFLAGS) $(LDLIBS)

stability: all
	$(B)/sph scripts/stability.lua

# the reference cases of ../shared/REFERENCES.md sections 1-4 at up to three resolutions:
# docs/validation.md and docs/validation_*.png (about 13 minutes on one thread, the default;
# make validate threads=2 for two)
validate: all
	$(B)/sph scripts/validate.lua $(if $(threads),threads=$(threads))

PREFIX ?= /usr/local
install: all
	install -d $(PREFIX)/bin $(PREFIX)/lib $(PREFIX)/include $(PREFIX)/share/lua/5.4/sph
	install -m 755 $(B)/sph $(PREFIX)/bin/sph
	install -m 644 $(B)/libsph.a $(PREFIX)/lib/
	install -m 644 src/sph.h $(PREFIX)/include/
	install -d $(PREFIX)/lib/lua/5.4
	install -m 755 $(B)/sph.so $(PREFIX)/lib/lua/5.4/sph.so
	install -m 644 lua/sph/*.lua $(PREFIX)/share/lua/5.4/sph/

clean:
	rm -rf build build-san

.PHONY: all test check bench stability validate install clean
-include $(wildcard $(B)/*.d)
