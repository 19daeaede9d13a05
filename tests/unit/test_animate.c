/* Animated PNG: write frames, assemble them, and decode the result with an independent
   decoder (Pillow, through /usr/bin/python3) that also checks every chunk's CRC with zlib
   and the APNG sequence numbers. A missing Pillow is a failure, not a skip. */
#include <cairo.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sph_pictures.h"
#include "unit.h"

static char dir[] = "/tmp/sph_test_animate_XXXXXX";

static char *tmp(char *buf, size_t len, const char *name) {
    snprintf(buf, len, "%s/%s", dir, name);
    return buf;
}

static int write_frame(const char *file, int w, int h, double r, double g, double b) {
    cairo_surface_t *s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
    cairo_t *cr = cairo_create(s);
    cairo_status_t st;
    cairo_set_source_rgb(cr, r, g, b);
    cairo_paint(cr);
    cairo_destroy(cr);
    st = cairo_surface_write_to_png(s, file);
    cairo_surface_destroy(s);
    return st == CAIRO_STATUS_SUCCESS ? 0 : -1;
}

/* Prints: n_frames is_animated, then per frame duration and the RGB of pixel (0, 0),
   then 1/0 for "all CRCs right" and "sequence numbers 0, 1, 2, ...". */
static const char decoder[] =
    "import sys, struct, zlib\n"
    "from PIL import Image\n"
    "f = sys.argv[1]\n"
    "im = Image.open(f)\n"
    "out = [im.n_frames, int(im.is_animated)]\n"
    "for i in range(im.n_frames):\n"
    "    im.seek(i)\n"
    "    out += [im.info[\"duration\"]] + list(im.convert(\"RGB\").getpixel((0, 0)))\n"
    "b = open(f, \"rb\").read()\n"
    "p, crc_ok, seqs = 8, 1, []\n"
    "while p < len(b):\n"
    "    n, t = struct.unpack(\">I4s\", b[p:p + 8])\n"
    "    crc = struct.unpack(\">I\", b[p + 8 + n:p + 12 + n])[0]\n"
    "    crc_ok &= zlib.crc32(b[p + 4:p + 8 + n]) == crc\n"
    "    if t in (b\"fcTL\", b\"fdAT\"): seqs.append(struct.unpack(\">I\", b[p + 8:p + 12])[0])\n"
    "    p += n + 12\n"
    "out += [crc_ok, int(seqs == list(range(len(seqs))))]\n"
    "print(\" \".join(str(x) for x in out))\n";

/* run the decoder on `file`; fill up to `cap` numbers; return how many were read */
static int decode(const char *file, double *v, int cap) {
    char cmd[8192], line[4096], *p, *end;
    FILE *fp;
    int n = 0;
    /* the script goes in single quotes: it uses only double quotes itself */
    snprintf(cmd, sizeof cmd, "/usr/bin/python3 -c '%s' '%s' 2>&1", decoder, file);
    fp = popen(cmd, "r");
    if (!fp)
        return 0;
    if (!fgets(line, sizeof line, fp))
        line[0] = 0;
    pclose(fp);
    for (p = line; n < cap; p = end) {
        v[n] = strtod(p, &end);
        if (end == p)
            break;
        n++;
    }
    if (n == 0)
        printf("# decoder said: %s\n", line);
    return n;
}

static void test_three_frames(void) {
    char f[3][256], out[256], err[256] = "";
    const char *frames[3] = {f[0], f[1], f[2]};
    double v[32], want[3][3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}};
    int i, n, rc, ok = 1;
    for (i = 0; i < 3; i++) {
        char name[32];
        snprintf(name, sizeof name, "f%d.png", i);
        tmp(f[i], sizeof f[i], name);
        write_frame(f[i], 64, 48, want[i][0] / 255, want[i][1] / 255, want[i][2] / 255);
    }
    rc = sph_animate_png(frames, 3, 25, 0, tmp(out, sizeof out, "anim.png"), err, sizeof err);
    CHECK(rc == 0, "animate 3 frames", "%s", err);
    n = decode(out, v, 32);
    CHECK(n == 16, "independent decoder (Pillow) reads the APNG", "got %d numbers", n);
    if (n != 16)
        return;
    CHECK(v[0] == 3 && v[1] == 1, "3 frames, animated", "n_frames %g is_animated %g", v[0], v[1]);
    for (i = 0; i < 3; i++) {
        ok &= fabs(v[2 + 4 * i] - 1000.0 / 25) < 1e-9;
        ok &=
            v[3 + 4 * i] == want[i][0] && v[4 + 4 * i] == want[i][1] && v[5 + 4 * i] == want[i][2];
    }
    CHECK(ok, "each frame lasts 1000/fps ms and shows its own picture", "durations %g %g %g", v[2],
          v[6], v[10]);
    CHECK(v[14] == 1, "every chunk CRC matches zlib's crc32", "bad CRC");
    CHECK(v[15] == 1, "fcTL/fdAT sequence numbers run 0, 1, 2, ...", "bad sequence");

    rc = sph_animate_png(frames, 1, 10, 1, out, err, sizeof err);
    n = decode(out, v, 32);
    CHECK(rc == 0 && n == 8 && v[0] == 1 && v[2] == 100, "a single frame at 10 fps",
          "rc %d n %d frames %g duration %g", rc, n, v[0], v[2]);
}

static void test_delay(void) {
    unsigned num = 0, den = 0;
    char err[128] = "";
    CHECK(sph_animate_delay(25, &num, &den, err, sizeof err) == 0 && num == 1 && den == 25,
          "25 fps is 1/25 s", "%u/%u", num, den);
    CHECK(sph_animate_delay(29.97, &num, &den, err, sizeof err) == 0 && num <= 65535 &&
              den <= 65535 && fabs((double)num / den - 1 / 29.97) < 1e-9,
          "29.97 fps as a 16-bit fraction", "%u/%u", num, den);
    CHECK(sph_animate_delay(0.5, &num, &den, err, sizeof err) == 0 && num == 2 && den == 1,
          "0.5 fps is 2 s", "%u/%u", num, den);
    CHECK(sph_animate_delay(0, &num, &den, err, sizeof err) == -1 && strstr(err, "fps"),
          "0 fps refused", "'%s'", err);
    CHECK(sph_animate_delay(NAN, &num, &den, err, sizeof err) == -1, "NaN fps refused", "accepted");
}

static void test_errors(void) {
    char a[256], b[256], c[256], out[256], err[512] = "";
    const char *frames[2] = {a, b};
    int rc;
    tmp(a, sizeof a, "big.png"), tmp(b, sizeof b, "small.png");
    write_frame(a, 64, 48, 1, 1, 1);
    write_frame(b, 64, 40, 0, 0, 0);
    tmp(out, sizeof out, "bad.png");
    rc = sph_animate_png(frames, 2, 25, 0, out, err, sizeof err);
    CHECK(rc == -1 && strstr(err, "64x40") && strstr(err, "64x48") && strstr(err, b),
          "frames of different sizes: message names frame and both sizes", "'%s'", err);
    CHECK(access(out, F_OK) != 0, "no half-written animation left", "%s exists", out);
    frames[1] = a;
    rc = sph_animate_png(frames, 2, 25, 0, "/nonexistent-dir/anim.png", err, sizeof err);
    CHECK(rc == -1 && strstr(err, "/nonexistent-dir/anim.png"),
          "output in a missing directory: -1 naming it", "'%s'", err);
    tmp(c, sizeof c, "missing.png");
    frames[1] = c;
    rc = sph_animate_png(frames, 2, 25, 0, out, err, sizeof err);
    CHECK(rc == -1 && strstr(err, c), "missing frame named", "'%s'", err);
    {
        FILE *fp = fopen(c, "wb");
        if (fp) {
            fputs("not a picture", fp);
            fclose(fp);
        }
    }
    rc = sph_animate_png(frames, 2, 25, 0, out, err, sizeof err);
    CHECK(rc == -1 && strstr(err, "not a PNG"), "non-PNG frame refused", "'%s'", err);
    { /* flip one byte inside the IHDR data: the CRC no longer matches */
        FILE *fp = fopen(a, "r+b");
        int ch;
        if (fp) {
            fseek(fp, 20, SEEK_SET);
            ch = fgetc(fp);
            fseek(fp, 20, SEEK_SET);
            fputc(ch ^ 0x40, fp);
            fclose(fp);
        }
    }
    frames[0] = a, frames[1] = a;
    rc = sph_animate_png(frames, 2, 25, 0, out, err, sizeof err);
    CHECK(rc == -1 && strstr(err, "CRC"), "damaged frame refused", "'%s'", err);
    rc = sph_animate_png(frames, 0, 25, 0, out, err, sizeof err);
    CHECK(rc == -1, "no frames refused", "accepted");
    frames[0] = out;
    rc = sph_animate_png(frames, 1, 25, 0, out, err, sizeof err);
    CHECK(rc == -1 && strstr(err, "also frame"), "output that is a frame refused", "'%s'", err);
    remove(a), remove(b), remove(c);
}

/* the whole of a file (up to cap bytes) and its length, -1 when it cannot be read */
static long slurp(const char *file, unsigned char *buf, size_t cap) {
    FILE *fp = fopen(file, "rb");
    if (!fp)
        return -1;
    size_t n = fread(buf, 1, cap, fp);
    fclose(fp);
    return (long)n;
}

/* files in the test directory (a temporary file left behind would show here) */
static int files_in_dir(void) {
    char cmd[512];
    snprintf(cmd, sizeof cmd, "ls -A '%s' | wc -l", dir);
    FILE *p = popen(cmd, "r");
    int n = -1;
    if (p) {
        if (fscanf(p, "%d", &n) != 1)
            n = -1;
        pclose(p);
    }
    return n;
}

/* An output that is a frame under another name ("dir/./b.png") was truncated before it was
   read, then removed; a failed animation removed an earlier animation at its path. */
static void test_output_kept(void) {
    static unsigned char before[1 << 16], after[1 << 16];
    char a[256], b[256], b_alias[256], out[256], small[256], err[512] = "";
    const char *frames[2] = {a, b_alias};
    int rc, files;
    long n0, n1;
    tmp(a, sizeof a, "ka.png"), tmp(b, sizeof b, "kb.png"), tmp(small, sizeof small, "ksmall.png");
    snprintf(b_alias, sizeof b_alias, "%s/./kb.png", dir);
    write_frame(a, 64, 48, 1, 0, 0);
    write_frame(b, 64, 48, 0, 0, 1);
    write_frame(small, 64, 40, 0, 1, 0);
    n0 = slurp(b, before, sizeof before);
    rc = sph_animate_png(frames, 2, 25, 0, b, err, sizeof err);
    n1 = slurp(b, after, sizeof after);
    CHECK(rc == -1 && strstr(err, "also frame 2"), "an output that is a frame under another name is refused",
          "rc %d '%s'", rc, err);
    CHECK(n0 > 0 && n1 == n0 && !memcmp(before, after, (size_t)n0), "that frame keeps its bytes",
          "%ld bytes before, %ld after", n0, n1);
    tmp(out, sizeof out, "kanim.png");
    frames[1] = b;
    rc = sph_animate_png(frames, 2, 25, 0, out, err, sizeof err);
    n0 = slurp(out, before, sizeof before);
    CHECK(rc == 0 && n0 > 0, "an animation made", "'%s'", err);
    files = files_in_dir();
    frames[1] = small;
    rc = sph_animate_png(frames, 2, 25, 0, out, err, sizeof err);
    n1 = slurp(out, after, sizeof after);
    CHECK(rc == -1 && n1 == n0 && !memcmp(before, after, (size_t)n0),
          "a failed animation leaves the earlier one at its path as it was", "rc %d, %ld bytes before, %ld after", rc,
          n0, n1);
    CHECK(files_in_dir() == files, "and leaves no temporary file", "%d files, %d before", files_in_dir(), files);
    remove(a), remove(b), remove(small), remove(out);
}

int main(void) {
    char buf[256];
    const char *names[] = {"f0.png", "f1.png", "f2.png", "anim.png"};
    size_t i;
    if (!mkdtemp(dir)) {
        printf("not ok - temporary directory: cannot create %s\n", dir);
        return 1;
    }
    test_three_frames();
    test_delay();
    test_errors();
    test_output_kept();
    for (i = 0; i < sizeof names / sizeof names[0]; i++)
        remove(tmp(buf, sizeof buf, names[i]));
    rmdir(dir);
    UNIT_END();
}
