/* animate.c: animated PNG from PNG frames, without re-encoding.

   APNG (Mozilla's specification, https://wiki.mozilla.org/APNG_Specification): after the
   signature and IHDR comes acTL (frame count, plays); each frame is an fcTL (its size,
   offset, delay) followed by its image data. The first frame's data stays in ordinary IDAT
   chunks, so a decoder without APNG support still shows frame 1; later frames go in fdAT
   chunks, which are IDAT data behind a 4-byte sequence number shared with the fcTLs. Every
   frame has the full image size, so each one's zlib stream (its IDAT data) is copied as
   is: frames must share the IHDR, i.e. size, bit depth, colour type and interlacing. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "atomic.h"
#include "message.h"
#include "sph_pictures.h"

typedef unsigned long u32; /* at least 32 bits; values are kept below 2^32 */

static const unsigned char png_signature[8] = {137, 80, 78, 71, 13, 10, 26, 10};

typedef struct {
    unsigned char *buf; /* the whole file */
    size_t len;
    const unsigned char *ihdr; /* 13 bytes */
    const unsigned char *plte; /* palette data or NULL */
    size_t plte_len;
    size_t first_idat; /* offset of the first IDAT chunk */
} png_file;

typedef struct {
    FILE *fp;
    u32 crc_table[256];
    u32 seq; /* APNG sequence number: fcTL and fdAT chunks, from 0 */
    int werr;
} writer;

/* CRC-32 of ISO 3309 / ITU-T V.42 as in the PNG specification (Annex D): reflected
   polynomial 0xedb88320, register preset to all ones and inverted at the end. */
static void crc_init(u32 t[256]) {
    u32 c, n;
    int k;
    for (n = 0; n < 256; n++) {
        c = n;
        for (k = 0; k < 8; k++)
            c = c & 1 ? 0xedb88320UL ^ (c >> 1) : c >> 1;
        t[n] = c;
    }
}

static u32 crc_update(const u32 t[256], u32 c, const unsigned char *p, size_t n) {
    size_t i;
    for (i = 0; i < n; i++)
        c = t[(c ^ p[i]) & 0xff] ^ (c >> 8);
    return c;
}

static u32 get32(const unsigned char *p) {
    return (u32)p[0] << 24 | (u32)p[1] << 16 | (u32)p[2] << 8 | (u32)p[3];
}

static void put32(unsigned char *p, u32 v) {
    p[0] = (unsigned char)(v >> 24), p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8), p[3] = (unsigned char)v;
}

static int read_all(const char *path, png_file *f, char *err, size_t errlen) {
    FILE *fp = fopen(path, "rb");
    size_t cap = 1 << 16, n;
    unsigned char *tmp;
    memset(f, 0, sizeof *f);
    if (!fp)
        return sph_message_set(err, errlen, "cannot read frame '%s': %s", path, strerror(errno));
    f->buf = malloc(cap);
    while (f->buf) {
        n = fread(f->buf + f->len, 1, cap - f->len, fp);
        f->len += n;
        if (f->len < cap)
            break;
        tmp = realloc(f->buf, cap *= 2);
        if (!tmp)
            free(f->buf);
        f->buf = tmp;
    }
    if (!f->buf) {
        fclose(fp);
        return sph_message_set(err, errlen, "out of memory reading frame '%s'", path);
    }
    if (ferror(fp)) {
        fclose(fp);
        free(f->buf);
        f->buf = NULL;
        return sph_message_set(err, errlen, "cannot read frame '%s': %s", path, strerror(errno));
    }
    fclose(fp);
    return 0;
}

/* Walk the chunks, checking lengths and CRCs; note IHDR, PLTE and the first IDAT. */
static int parse(const char *path, png_file *f, const u32 crc[256], char *err, size_t errlen) {
    size_t pos = 8, len;
    if (f->len < 8 || memcmp(f->buf, png_signature, 8) != 0)
        return sph_message_set(err, errlen, "frame '%s' is not a PNG file", path);
    for (;;) {
        const unsigned char *c = f->buf + pos;
        if (f->len - pos < 12)
            return sph_message_set(err, errlen, "frame '%s' is truncated (no IEND chunk)", path);
        len = get32(c);
        if (len > f->len - pos - 12)
            return sph_message_set(err, errlen, "frame '%s' is truncated (chunk at byte %zu)", path, pos);
        if ((crc_update(crc, 0xffffffffUL, c + 4, len + 4) ^ 0xffffffffUL) != get32(c + 8 + len))
            return sph_message_set(err, errlen, "frame '%s' is damaged (bad CRC at byte %zu)", path, pos);
        if (pos == 8 && (memcmp(c + 4, "IHDR", 4) != 0 || len != 13))
            return sph_message_set(err, errlen, "frame '%s' does not start with an IHDR chunk", path);
        if (pos == 8)
            f->ihdr = c + 8;
        else if (!memcmp(c + 4, "PLTE", 4))
            f->plte = c + 8, f->plte_len = len;
        else if (!memcmp(c + 4, "IDAT", 4) && !f->first_idat)
            f->first_idat = pos;
        else if (!memcmp(c + 4, "IEND", 4))
            break;
        pos += len + 12;
    }
    if (!f->first_idat)
        return sph_message_set(err, errlen, "frame '%s' has no image data (IDAT)", path);
    return 0;
}

/* One chunk: length, type, `pre` (a sequence number or nothing), data, CRC. */
static void put_chunk(writer *w, const char *type, const unsigned char *pre, size_t npre,
                      const unsigned char *data, size_t n) {
    unsigned char b[8];
    u32 c;
    put32(b, (u32)(npre + n));
    memcpy(b + 4, type, 4);
    c = crc_update(w->crc_table, 0xffffffffUL, b + 4, 4);
    if (npre)
        c = crc_update(w->crc_table, c, pre, npre);
    if (n)
        c = crc_update(w->crc_table, c, data, n);
    if (fwrite(b, 1, 8, w->fp) != 8 || (npre && fwrite(pre, 1, npre, w->fp) != npre) ||
        (n && fwrite(data, 1, n, w->fp) != n))
        w->werr = 1;
    put32(b, c ^ 0xffffffffUL);
    if (fwrite(b, 1, 4, w->fp) != 4)
        w->werr = 1;
}

/* Frame control: full-size frame at (0, 0), shown for num/den seconds, replacing the
   canvas (dispose NONE, blend SOURCE: frames are opaque pictures, not overlays). */
static void put_fctl(writer *w, const unsigned char *ihdr, unsigned num, unsigned den) {
    unsigned char b[26] = {0};
    put32(b, w->seq++);
    memcpy(b + 4, ihdr, 8); /* width, height */
    b[20] = (unsigned char)(num >> 8), b[21] = (unsigned char)num;
    b[22] = (unsigned char)(den >> 8), b[23] = (unsigned char)den;
    put_chunk(w, "fcTL", NULL, 0, b, sizeof b);
}

/* Copy frame f's image data: IDAT for the first frame, fdAT (numbered) for the rest. */
static void put_data(writer *w, const png_file *f, int first) {
    size_t pos = f->first_idat, len;
    unsigned char seq[4];
    while (pos + 12 <= f->len) {
        const unsigned char *c = f->buf + pos;
        len = get32(c);
        if (!memcmp(c + 4, "IEND", 4))
            break;
        if (!memcmp(c + 4, "IDAT", 4)) {
            if (first) {
                put_chunk(w, "IDAT", NULL, 0, c + 8, len);
            } else {
                put32(seq, w->seq++);
                put_chunk(w, "fdAT", seq, 4, c + 8, len);
            }
        }
        pos += len + 12;
    }
}

int sph_animate_delay(double fps, unsigned *num, unsigned *den, char *err, size_t errlen) {
    double x, d, a;
    u32 h = 1, k = 0, h2 = 0, k2 = 1, hn, kn;
    int i;
    if (!isfinite(fps) || !(fps > 0))
        return sph_message_set(err, errlen, "fps must be a positive number (got %g)", fps);
    d = 1 / fps;
    if (d > 65535 || d < 1.0 / 65535)
        return sph_message_set(err, errlen, "fps %g is out of range (1/65535 .. 65535)", fps);
    if (fps == floor(fps)) { /* the common case, exactly */
        *num = 1, *den = (unsigned)fps;
        return 0;
    }
    /* best continued-fraction convergent of d with both terms within 16 bits */
    x = d;
    for (i = 0; i < 64; i++) {
        a = floor(x);
        hn = (u32)a * h + h2, kn = (u32)a * k + k2;
        if (hn > 65535 || kn > 65535)
            break;
        h2 = h, k2 = k, h = hn, k = kn;
        if (x - a < 1e-12)
            break;
        x = 1 / (x - a);
    }
    if (h == 0 || k == 0)
        return sph_message_set(err, errlen, "fps %g has no delay fraction within 16 bits", fps);
    *num = (unsigned)h, *den = (unsigned)k;
    return 0;
}

int sph_animate_png(const char *const *frames, size_t nframes, double fps, int loops,
                    const char *file, char *err, size_t errlen) {
    png_file first, cur;
    writer w;
    sph_atomic_file out;
    unsigned num, den;
    unsigned char actl[8];
    size_t i, pos;
    int rc = 0;
    if (!frames || nframes == 0)
        return sph_message_set(err, errlen, "no frames to animate");
    if (nframes > 0x7fffffffUL)
        return sph_message_set(err, errlen, "too many frames (%zu)", nframes);
    if (!file || !*file)
        return sph_message_set(err, errlen, "no output file name");
    if (loops < 0)
        return sph_message_set(err, errlen, "loops must be >= 0 (0: forever), got %d", loops);
    /* The output may not be a frame: the same file under any name ("./b.png", a link),
     * told by device and inode; the name too, for an output not there yet. */
    struct stat out_st;
    int out_exists = stat(file, &out_st) == 0;
    for (i = 0; i < nframes; i++) {
        struct stat fr_st;
        if (!frames[i])
            return sph_message_set(err, errlen, "frame %zu has no file name", i + 1);
        if (!strcmp(frames[i], file) || (out_exists && stat(frames[i], &fr_st) == 0 &&
                                         fr_st.st_dev == out_st.st_dev && fr_st.st_ino == out_st.st_ino))
            return sph_message_set(err, errlen, "output '%s' is also frame %zu ('%s')", file, i + 1, frames[i]);
    }
    if (sph_animate_delay(fps, &num, &den, err, errlen))
        return -1;
    memset(&w, 0, sizeof w);
    crc_init(w.crc_table);
    if (read_all(frames[0], &first, err, errlen)) /* before creating the output */
        return -1;
    if (parse(frames[0], &first, w.crc_table, err, errlen)) {
        free(first.buf);
        return -1;
    }
    if (sph_atomic_open(&out, file, err, errlen)) {
        free(first.buf);
        return -1;
    }
    w.fp = out.fp;
    if (fwrite(png_signature, 1, 8, w.fp) != 8)
        w.werr = 1;
    put_chunk(&w, "IHDR", NULL, 0, first.ihdr, 13);
    put32(actl, (u32)nframes), put32(actl + 4, (u32)loops);
    put_chunk(&w, "acTL", NULL, 0, actl, 8);
    /* chunks of frame 1 between IHDR and IDAT (PLTE, tRNS, gAMA, ...) describe them all */
    for (pos = 8 + 25; pos < first.first_idat; pos += get32(first.buf + pos) + 12) {
        const unsigned char *c = first.buf + pos;
        if (memcmp(c + 4, "acTL", 4) && memcmp(c + 4, "fcTL", 4))
            put_chunk(&w, (const char *)c + 4, NULL, 0, c + 8, get32(c));
    }
    put_fctl(&w, first.ihdr, num, den);
    put_data(&w, &first, 1);
    for (i = 1; i < nframes && rc == 0 && !w.werr; i++) {
        rc = read_all(frames[i], &cur, err, errlen);
        if (rc == 0)
            rc = parse(frames[i], &cur, w.crc_table, err, errlen);
        if (rc == 0 && memcmp(cur.ihdr, first.ihdr, 8) != 0)
            rc = sph_message_set(err, errlen,
                      "frame '%s' is %lux%lu but frame '%s' is %lux%lu: all frames "
                      "must have the same size",
                      frames[i], get32(cur.ihdr), get32(cur.ihdr + 4), frames[0], get32(first.ihdr),
                      get32(first.ihdr + 4));
        if (rc == 0 && memcmp(cur.ihdr, first.ihdr, 13) != 0)
            rc = sph_message_set(err, errlen,
                      "frame '%s' differs from frame '%s' in bit depth, colour "
                      "type or interlacing",
                      frames[i], frames[0]);
        if (rc == 0 && first.plte &&
            (!cur.plte || cur.plte_len != first.plte_len ||
             memcmp(cur.plte, first.plte, first.plte_len) != 0))
            rc = sph_message_set(err, errlen, "frame '%s' has a different palette from frame '%s'", frames[i],
                      frames[0]);
        if (rc == 0) {
            put_fctl(&w, first.ihdr, num, den);
            put_data(&w, &cur, 0);
        }
        free(cur.buf);
    }
    free(first.buf);
    if (rc == 0)
        put_chunk(&w, "IEND", NULL, 0, NULL, 0);
    if (rc == 0 && w.werr)
        rc = sph_message_set(err, errlen, "cannot write '%s': %s", file, strerror(errno));
    /* a failure leaves no half animation, and an earlier file at that path as it was */
    if (rc != 0) {
        sph_atomic_abort(&out);
        return rc;
    }
    return sph_atomic_commit(&out, err, errlen);
}
