/* Particle output: CSV (one row per particle), legacy VTK polydata, VTK XML unstructured
 * grids (.vtu, binary) and their time series (.pvd), for ParaView and anything else.
 *
 * One table of per-particle quantities (FIELDS below) gives every file its names: those of
 * w:field / sph_world_field, so a script, a CSV column and a ParaView array say the same
 * thing. Every writer goes through a temporary file renamed into place (atomic.h): a
 * failed write leaves an earlier file at that path as it was, and no partial file. */
#include "internal.h"
#include "atomic.h"
#include "message.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the quantities written for every particle (fluid and wall) ------------------- */

enum { Q_ID, Q_KIND, Q_MATERIAL, Q_U, Q_V, Q_P, Q_RHO, Q_ETA, Q_GAMMADOT, Q_STRESS, Q_YIELDED, Q_SURFACE };

typedef struct {
    const char *name;
    int q;       /* Q_* */
    int integer; /* written as an integer */
} field;

/* The files' particle data, in this order (x, y are the points; velocity is the VTK
 * vector (u, v, 0) besides u and v). Names as in sph_world_field. */
static const field FIELDS[] = {
    {"id", Q_ID, 1},       {"kind", Q_KIND, 1},     {"u", Q_U, 0},     {"v", Q_V, 0},
    {"p", Q_P, 0},         {"rho", Q_RHO, 0},       {"eta", Q_ETA, 0}, {"gammadot", Q_GAMMADOT, 0},
    {"stress", Q_STRESS, 0}, {"yielded", Q_YIELDED, 1}, {"surface", Q_SURFACE, 1}, {"material", Q_MATERIAL, 1},
};
#define NFIELDS ((int)(sizeof FIELDS / sizeof FIELDS[0]))

/* A copy of the particles: 0 the simulated ones, bit 0 mirrored across the x symmetry
 * plane, bit 1 across the y one (positions reflected, the normal velocity negated). */
typedef struct {
    const sph_world *w;
    int copy;  /* the reflections */
    int index; /* its place among the copies written: ids of copy k are offset by k next_id */
} view;

static double pos(const view *c, int i, int axis) {
    const sph_world *w = c->w;
    double x = axis ? w->y[i] : w->x[i];
    if (c->copy & (1 << axis)) x = 2 * w->par.sym_at[axis] - x;
    return x;
}

static double quantity(const view *c, int i, int q) {
    const sph_world *w = c->w;
    int fl = w->kind[i] == SPH_FLUID;
    switch (q) {
    case Q_ID: return (double)w->id[i] + 1 + (double)c->index * w->next_id; /* copies: ids after the originals' */
    case Q_KIND: return fl ? 0 : w->kind[i] + 1;
    case Q_MATERIAL: return fl ? w->mat[i] + 1 : 0;
    case Q_U:
    case Q_V: {
        int a = q == Q_V;
        /* a wall particle moves with its plate, along the plate's axis */
        double u = fl ? (a ? w->v[i] : w->u[i]) : w->plates[w->kind[i]].axis == a ? w->plates[w->kind[i]].vel : 0.0;
        return (c->copy & (1 << a)) ? -u : u;
    }
    case Q_P: return w->p[i];
    case Q_RHO: return w->rho[i];
    case Q_ETA: return fl ? w->eta[i] : 0;
    case Q_GAMMADOT: return fl ? w->gd[i] : 0;
    case Q_STRESS: return fl ? sph_particle_stress(w, i) : 0;
    case Q_YIELDED: return fl && sph_particle_yielded(w, i);
    case Q_SURFACE: return fl ? w->surf[i] : 0;
    }
    return 0;
}

/* The shortest of %.15g, %.16g, %.17g that reads back as t: times as people write them
 * (0.025, not 0.025000000000000001), exact all the same. */
static const char *exact(char buf[40], double t) {
    for (int digits = 15; digits <= 17; digits++) {
        snprintf(buf, 40, "%.*g", digits, t);
        if (strtod(buf, NULL) == t) break;
    }
    return buf;
}

static int openf(sph_world *w, sph_atomic_file *af, const char *file) {
    char why[512];
    if (sph_atomic_open(af, file, why, sizeof why)) return sph_world_fail(w, "%s", why);
    return 0;
}

static int closef(sph_world *w, sph_atomic_file *af) {
    char why[512];
    if (sph_atomic_commit(af, why, sizeof why)) return sph_world_fail(w, "%s", why);
    return 0;
}

int sph_io_write_csv(sph_world *w, const char *file);
int sph_io_write_vtk(sph_world *w, const char *file);

/* ---- CSV ------------------------------------------------------------------------- */

int sph_io_write_csv(sph_world *w, const char *file) {
    sph_atomic_file af;
    if (openf(w, &af, file)) return -1;
    FILE *f = af.fp;
    view c = {w, 0, 0};
    /* id, kind, then the points, then the rest in the table's order */
    fprintf(f, "id,kind,x,y");
    for (int k = 2; k < NFIELDS; k++) fprintf(f, ",%s", FIELDS[k].name);
    fputc('\n', f);
    for (int i = 0; i < w->n; i++) {
        fprintf(f, "%d,%d,%.10g,%.10g", (int)quantity(&c, i, Q_ID), (int)quantity(&c, i, Q_KIND), w->x[i], w->y[i]);
        for (int k = 2; k < NFIELDS; k++) {
            double v = quantity(&c, i, FIELDS[k].q);
            if (FIELDS[k].integer) fprintf(f, ",%d", (int)v);
            else fprintf(f, ",%.10g", v);
        }
        fputc('\n', f);
    }
    return closef(w, &af);
}

/* ---- legacy VTK (ASCII polydata) ---------------------------------------------------- */

int sph_io_write_vtk(sph_world *w, const char *file) {
    sph_atomic_file af;
    if (openf(w, &af, file)) return -1;
    FILE *f = af.fp;
    int n = w->n;
    view c = {w, 0, 0};
    fprintf(f, "# vtk DataFile Version 3.0\nsph particles t=%.10g\nASCII\nDATASET POLYDATA\n", w->t);
    fprintf(f, "POINTS %d double\n", n);
    for (int i = 0; i < n; i++) fprintf(f, "%.10g %.10g 0\n", w->x[i], w->y[i]);
    fprintf(f, "VERTICES %d %d\n", n, 2 * n);
    for (int i = 0; i < n; i++) fprintf(f, "1 %d\n", i);
    fprintf(f, "POINT_DATA %d\n", n);
    fprintf(f, "VECTORS velocity double\n");
    for (int i = 0; i < n; i++) fprintf(f, "%.10g %.10g 0\n", quantity(&c, i, Q_U), quantity(&c, i, Q_V));
    for (int k = 0; k < NFIELDS; k++) {
        fprintf(f, "SCALARS %s %s 1\nLOOKUP_TABLE default\n", FIELDS[k].name, FIELDS[k].integer ? "int" : "double");
        for (int i = 0; i < n; i++) {
            double v = quantity(&c, i, FIELDS[k].q);
            if (FIELDS[k].integer) fprintf(f, "%d\n", (int)v);
            else fprintf(f, "%.10g\n", v);
        }
    }
    return closef(w, &af);
}

/* ---- VTK XML (.vtu): binary data, little-endian ------------------------------------ */

/* Bytes out, either straight (raw appended data) or base64-encoded (inline data), through
 * a buffer. The base64 stream of one DataArray holds its header and its data together
 * (as VTK's own writer encodes uncompressed data): one padding, at the end. */
typedef struct {
    FILE *f;
    int b64;
    unsigned char in[3];
    int nin;
    unsigned char buf[4096];
    size_t nbuf;
} sink;

static void sink_put(sink *s, unsigned char c) {
    if (s->nbuf == sizeof s->buf) {
        fwrite(s->buf, 1, s->nbuf, s->f);
        s->nbuf = 0;
    }
    s->buf[s->nbuf++] = c;
}

static const char B64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

static void b64_group(sink *s, int n) {
    unsigned v = (unsigned)s->in[0] << 16 | (unsigned)(n > 1 ? s->in[1] : 0) << 8 | (unsigned)(n > 2 ? s->in[2] : 0);
    sink_put(s, (unsigned char)B64[v >> 18 & 63]);
    sink_put(s, (unsigned char)B64[v >> 12 & 63]);
    sink_put(s, n > 1 ? (unsigned char)B64[v >> 6 & 63] : '=');
    sink_put(s, n > 2 ? (unsigned char)B64[v & 63] : '=');
}

static void sink_byte(sink *s, unsigned char c) {
    if (!s->b64) {
        sink_put(s, c);
        return;
    }
    s->in[s->nin++] = c;
    if (s->nin == 3) {
        b64_group(s, 3);
        s->nin = 0;
    }
}

/* little-endian, whatever the host's order */
static void sink_uint(sink *s, uint64_t v, int bytes) {
    for (int k = 0; k < bytes; k++) sink_byte(s, (unsigned char)(v >> (8 * k) & 0xff));
}

static void sink_f64(sink *s, double d) {
    uint64_t v;
    memcpy(&v, &d, sizeof v);
    sink_uint(s, v, 8);
}

/* end of one base64 stream (one DataArray): the last group, padded */
static void sink_end(sink *s) {
    if (s->b64 && s->nin) b64_group(s, s->nin);
    s->nin = 0;
}

static void sink_flush(sink *s) {
    if (s->nbuf) fwrite(s->buf, 1, s->nbuf, s->f);
    s->nbuf = 0;
}

/* The arrays of a .vtu, in file order. */
enum { A_POINTS, A_CONNECTIVITY, A_OFFSETS, A_TYPES, A_VELOCITY, A_FIELD /* + k */ };
#define NARRAYS (A_FIELD + NFIELDS)

typedef struct {
    const char *name, *type;
    int ncomp, word;
} array_info;

static array_info array_of(int a) {
    array_info r = {0, 0, 1, 8};
    switch (a) {
    case A_POINTS: r.name = "Points", r.type = "Float64", r.ncomp = 3; break;
    case A_CONNECTIVITY: r.name = "connectivity", r.type = "Int64"; break;
    case A_OFFSETS: r.name = "offsets", r.type = "Int64"; break;
    case A_TYPES: r.name = "types", r.type = "UInt8", r.word = 1; break;
    case A_VELOCITY: r.name = "velocity", r.type = "Float64", r.ncomp = 3; break;
    default:
        r.name = FIELDS[a - A_FIELD].name;
        if (FIELDS[a - A_FIELD].integer) r.type = "Int32", r.word = 4;
        else r.type = "Float64";
    }
    return r;
}

/* One array's data (after its header): every copy of the particles, in order. */
static void array_data(sink *s, const sph_world *w, int a, int ncopy, const int *copies) {
    long long k = 0;
    for (int c = 0; c < ncopy; c++) {
        view v = {w, copies[c], c};
        for (int i = 0; i < w->n; i++, k++) {
            switch (a) {
            case A_POINTS:
                sink_f64(s, pos(&v, i, 0)), sink_f64(s, pos(&v, i, 1)), sink_f64(s, 0.0);
                break;
            case A_CONNECTIVITY: sink_uint(s, (uint64_t)k, 8); break;
            case A_OFFSETS: sink_uint(s, (uint64_t)(k + 1), 8); break;
            case A_TYPES: sink_byte(s, 1); break; /* VTK_VERTEX */
            case A_VELOCITY:
                sink_f64(s, quantity(&v, i, Q_U)), sink_f64(s, quantity(&v, i, Q_V)), sink_f64(s, 0.0);
                break;
            default: {
                const field *fd = &FIELDS[a - A_FIELD];
                double x = quantity(&v, i, fd->q);
                if (fd->integer) sink_uint(s, (uint64_t)(uint32_t)(int32_t)x, 4);
                else sink_f64(s, x);
            }
            }
        }
    }
}

void sph_vtu_defaults(const sph_world *w, sph_vtu_options *o) {
    memset(o, 0, sizeof *o);
    o->header64 = 1;
    o->mirror = w && (w->par.symmetry[0] || w->par.symmetry[1]);
}

int sph_world_write_vtu(sph_world *w, const char *file, const sph_vtu_options *opt) {
    sph_vtu_options o;
    if (opt) o = *opt;
    else sph_vtu_defaults(w, &o);
    /* the copies: the particles, then their mirror images across each symmetry plane */
    int copies[4] = {0}, ncopy = 1;
    if (o.mirror) {
        int planes = (w->par.symmetry[0] ? 1 : 0) | (w->par.symmetry[1] ? 2 : 0);
        for (int c = 1; c < 4; c++)
            if ((c & planes) == c) copies[ncopy++] = c;
    }
    uint64_t npts = (uint64_t)w->n * (uint64_t)ncopy;
    int hbytes = o.header64 ? 8 : 4;
    uint64_t bytes[NARRAYS];
    for (int a = 0; a < NARRAYS; a++) {
        array_info ai = array_of(a);
        bytes[a] = npts * (uint64_t)ai.ncomp * (uint64_t)ai.word;
        if (!o.header64 && bytes[a] > 0xffffffffu)
            return sph_world_fail(w, "cannot write '%s': array %s holds %llu bytes, more than a UInt32 header "
                                     "counts (use header_type = \"UInt64\")", file, ai.name,
                                     (unsigned long long)bytes[a]);
    }
    sph_atomic_file af;
    if (openf(w, &af, file)) return -1;
    FILE *f = af.fp;
    sink s;
    memset(&s, 0, sizeof s);
    s.f = f;
    s.b64 = !o.appended;
    uint64_t offset = 0;
    char tbuf[40];
    exact(tbuf, w->t);
    fprintf(f, "<?xml version=\"1.0\"?>\n<!-- sph %s particles, t = %s -->\n"
               "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"%s\">\n"
               "  <UnstructuredGrid>\n"
               "    <FieldData>\n"
               "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">%s</DataArray>\n"
               "    </FieldData>\n"
               "    <Piece NumberOfPoints=\"%llu\" NumberOfCells=\"%llu\">\n",
            SPH_VERSION, tbuf, o.header64 ? "UInt64" : "UInt32", tbuf, (unsigned long long)npts,
            (unsigned long long)npts);
    for (int a = 0; a < NARRAYS; a++) {
        array_info ai = array_of(a);
        if (a == A_POINTS) fprintf(f, "      <Points>\n");
        if (a == A_CONNECTIVITY) fprintf(f, "      <Cells>\n");
        if (a == A_VELOCITY) fprintf(f, "      <PointData Scalars=\"p\" Vectors=\"velocity\">\n");
        fprintf(f, "        <DataArray type=\"%s\" Name=\"%s\"", ai.type, ai.name);
        if (ai.ncomp > 1) fprintf(f, " NumberOfComponents=\"%d\"", ai.ncomp);
        if (o.appended) {
            fprintf(f, " format=\"appended\" offset=\"%llu\"/>\n", (unsigned long long)offset);
            offset += (uint64_t)hbytes + bytes[a];
        } else {
            fprintf(f, " format=\"binary\">\n          ");
            sink_uint(&s, bytes[a], hbytes);
            array_data(&s, w, a, ncopy, copies);
            sink_end(&s);
            sink_flush(&s);
            fprintf(f, "\n        </DataArray>\n");
        }
        if (a == A_POINTS) fprintf(f, "      </Points>\n");
        if (a == A_TYPES) fprintf(f, "      </Cells>\n");
        if (a == NARRAYS - 1) fprintf(f, "      </PointData>\n");
    }
    fprintf(f, "    </Piece>\n  </UnstructuredGrid>\n");
    if (o.appended) {
        fprintf(f, "  <AppendedData encoding=\"raw\">\n   _");
        for (int a = 0; a < NARRAYS; a++) {
            sink_uint(&s, bytes[a], hbytes);
            array_data(&s, w, a, ncopy, copies);
        }
        sink_flush(&s);
        fprintf(f, "\n  </AppendedData>\n");
    }
    fprintf(f, "</VTKFile>\n");
    return closef(w, &af);
}

/* ---- .pvd: a time series of files ------------------------------------------------- */

/* s as an XML attribute value (between double quotes) */
static void xml_attr(FILE *f, const char *s) {
    for (; *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        case '\'': fputs("&apos;", f); break;
        case '\n': fputs("&#10;", f); break;
        case '\t': fputs("&#9;", f); break;
        case '\r': fputs("&#13;", f); break;
        default: fputc(*s, f);
        }
    }
}

int sph_write_pvd(const char *file, size_t n, const double *t, const char *const *files, char *err,
                  size_t errlen) {
    for (size_t k = 0; k < n; k++) {
        if (!isfinite(t[k])) return sph_message_set(err, errlen, "entry %zu: time %g is not finite", k + 1, t[k]);
        if (!files[k] || !*files[k]) return sph_message_set(err, errlen, "entry %zu: no file name", k + 1);
        for (const unsigned char *c = (const unsigned char *)files[k]; *c; c++)
            if (*c < 0x20 && *c != '\t' && *c != '\n' && *c != '\r')
                return sph_message_set(err, errlen, "entry %zu: file name holds a control character", k + 1);
    }
    sph_atomic_file af;
    if (sph_atomic_open(&af, file, err, errlen)) return -1;
    FILE *f = af.fp;
    fprintf(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
               "  <Collection>\n");
    for (size_t k = 0; k < n; k++) {
        char tbuf[40];
        fprintf(f, "    <DataSet timestep=\"%s\" group=\"\" part=\"0\" file=\"", exact(tbuf, t[k]));
        xml_attr(f, files[k]);
        fprintf(f, "\"/>\n");
    }
    fprintf(f, "  </Collection>\n</VTKFile>\n");
    return sph_atomic_commit(&af, err, errlen);
}

int sph_world_write_csv(sph_world *w, const char *file) { return sph_io_write_csv(w, file); }
int sph_world_write_vtk(sph_world *w, const char *file) { return sph_io_write_vtk(w, file); }
