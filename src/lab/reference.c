/* Reference runs, their cache on disk and the error of a run against its
 * reference (see ss_reference.h). The cache file, all integers and floats in
 * the machine's byte order (a file from another machine fails its checks and
 * is recomputed):
 *   "SSREF\0v1"  8 bytes magic
 *   key          uint64
 *   version, frames, nvert, nface   int32 each
 *   mean edge    double
 *   rest         double (nvert x 3)
 *   faces        int32  (nface x 3)
 *   positions    double (frames x nvert x 3)
 *   checksum     uint64: FNV-1a of every byte before it */
#include "ss_reference.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "skin_sim/ss_settings.h"
#include "ss_track.h"
#include "bvh.h"
#include "ss_code_digest.h"
#include "ss_err.h"
#include "ss_free.h"

static const char MAGIC[8] = {'S', 'S', 'R', 'E', 'F', '\0', 'v', '1'};
#define MAX_COUNT 100000000

ss_run_settings ss_reference_settings(const ss_run_settings *run) {
  ss_run_settings r = *run;
  const ss_sim_settings def = ss_sim_default_settings();
  r.skin = NULL;
  /* the run's model is the reference's (run settings only differ below) when
   * it is of the welded body, not of a skin of the run's own */
  if (run->skin) r.model = NULL;
  r.settle = 0.0; /* the reference covers the motion's frames only */
  r.sim.solver = SS_SOLVER_NEWTON;
  r.sim.substeps = run->sim.substeps > SS_REFERENCE_SUBSTEPS ? run->sim.substeps
                                                             : SS_REFERENCE_SUBSTEPS;
  r.sim.iterations = SS_REFERENCE_ITERATIONS;
  r.sim.tol = run->sim.tol > 0.0 && run->sim.tol < SS_REFERENCE_TOL ? run->sim.tol
                                                                    : SS_REFERENCE_TOL;
  /* unused by Newton (the safety net is quasi-Newton's): keeps keys equal */
  r.sim.lbfgs_history = def.lbfgs_history;
  r.sim.safety_residual = def.safety_residual;
  r.sim.iterations_max = def.iterations_max;
  r.sim.dt = def.dt;                       /* a run steps 1 / fps whatever dt says */
  if (r.sim.mover.method != SS_METHOD_NRING) r.sim.mover.nring_rings = def.mover.nring_rings;
  return r;
}

ss_run_settings ss_truth_settings(const ss_run_settings *run) {
  ss_run_settings t = *run;
  t.sim.mover = ss_mover_default_settings();
  t.sim.substeps = SS_REFERENCE_SUBSTEPS;
  return ss_reference_settings(&t);
}

/* ---- the key ----------------------------------------------------------------- */

typedef struct text_buf {
  char *s;
  size_t n, cap;
} text_buf;

static void text_add(text_buf *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void text_add(text_buf *t, const char *fmt, ...) {
  if (!t->s) return;
  for (;;) {
    va_list ap;
    va_start(ap, fmt);
    int k = vsnprintf(t->s + t->n, t->cap - t->n, fmt, ap);
    va_end(ap);
    if (k < 0) return;
    if ((size_t)k < t->cap - t->n) {
      t->n += (size_t)k;
      return;
    }
    char *bigger = realloc(t->s, 2 * t->cap + (size_t)k);
    if (!bigger) {
      free(t->s);
      t->s = NULL;
      return;
    }
    t->s = bigger;
    t->cap = 2 * t->cap + (size_t)k;
  }
}

static int run_frames(const ss_body *body, const ss_run_settings *run) {
  return run->frames > 0 ? run->frames : (body->frames > 0 ? body->frames : 1);
}

int ss_reference_key(const ss_body *body, const ss_run_settings *run, unsigned long long *key,
                     char *err, int err_sz) {
  if (!body || !run || !key || !body->pose || body->nvert <= 0 || body->nface <= 0)
    return ss_fail(err, err_sz, SS_E_ARG, "reference: NULL argument or empty body");
  const ss_run_settings r = ss_reference_settings(run);
  const ss_sim_settings *s = &r.sim;
  const int frames = run_frames(body, run);
  double *pos = malloc(sizeof(double) * 3 * (size_t)body->nvert);
  text_buf t = {malloc(1024), 0, 1024};
  if (!pos || !t.s) {
    free(pos);
    free(t.s);
    return ss_fail(err, err_sz, SS_E_NOMEM, "reference: out of memory for the key");
  }
  /* the body: rest mesh and pose at every frame */
  unsigned long long motion = 1469598103934665603ULL;
  for (int f = 0; f <= frames; f++) {
    int status = body->pose(body->user, (double)f, pos);
    if (status) {
      free(pos);
      free(t.s);
      return ss_fail(err, err_sz, status, "reference: the body's pose at frame %d failed (%s)", f,
                     ss_status_string(status));
    }
    motion = motion * 1099511628211ULL ^
             ss_hash_bytes(pos, sizeof(double) * 3 * (size_t)body->nvert);
  }
  free(pos);
  text_add(&t, "skin_sim reference %d code %s\n", SS_REFERENCE_VERSION, SS_CODE_DIGEST);
  text_add(&t, "body %d %d rest %016llx faces %016llx motion %016llx fps %a frames %d\n",
           body->nvert, body->nface,
           ss_hash_bytes(body->rest, sizeof(double) * 3 * (size_t)body->nvert),
           ss_hash_bytes(body->faces, sizeof(int) * 3 * (size_t)body->nface), motion, body->fps,
           frames);
  /* every setting of the table that can change the result (threads cannot) */
  int nset = 0;
  const ss_setting *table = ss_settings_table(&nset);
  for (int i = 0; i < nset; i++) {
    const ss_setting *d = &table[i];
    if (!d->in_key) continue;
    if (d->type == SS_SETTING_DOUBLE)
      text_add(&t, "%s %a\n", d->name, ss_setting_get(d, s, 0));
    else if (d->type == SS_SETTING_VEC3)
      text_add(&t, "%s %a %a %a\n", d->name, ss_setting_get(d, s, 0), ss_setting_get(d, s, 1),
               ss_setting_get(d, s, 2));
    else
      text_add(&t, "%s %d\n", d->name, (int)ss_setting_get(d, s, 0));
  }
  if (s->face_mask)
    text_add(&t, "mask %016llx\n", ss_hash_bytes(s->face_mask, (size_t)body->nface));
  else
    text_add(&t, "mask none\n");
  if (!t.s) return ss_fail(err, err_sz, SS_E_NOMEM, "reference: out of memory for the key");
  *key = ss_hash_bytes(t.s, t.n);
  free(t.s);
  return SS_OK;
}

/* ---- the cache file ---------------------------------------------------------- */

void ss_reference_destroy(ss_reference *ref) {
  if (!ref) return;
  SS_FREE_ALL(ref->rest, ref->faces, ref->pos, ref);
}

static void cache_path(char *path, size_t n, const char *dir, unsigned long long key) {
  snprintf(path, n, "%s/ref_%016llx.bin", dir, key);
}

typedef struct hashed_file {
  FILE *f;
  unsigned long long h;
} hashed_file;

static void hash_more(unsigned long long *h, const void *data, size_t n) {
  const unsigned char *p = data;
  for (size_t i = 0; i < n; i++) {
    *h ^= p[i];
    *h *= 1099511628211ULL;
  }
}

static int hf_read(hashed_file *hf, void *data, size_t size, size_t count) {
  if (fread(data, size, count, hf->f) != count) return -1;
  hash_more(&hf->h, data, size * count);
  return 0;
}

static int hf_write(hashed_file *hf, const void *data, size_t size, size_t count) {
  hash_more(&hf->h, data, size * count);
  return fwrite(data, size, count, hf->f) == count ? 0 : -1;
}

static size_t file_size(int frames, int nvert, int nface) {
  return 8 + 8 + 4 * 4 + 8 + sizeof(double) * 3 * (size_t)nvert + 4 * 3 * (size_t)nface +
         sizeof(double) * 3 * (size_t)nvert * (size_t)frames + 8;
}

/* Reads a valid cache file into ref (key and frames set by the caller).
 * Returns 0 if read, 1 if absent, -1 if present but invalid. */
static int cache_read(ss_reference *ref, const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return 1;
  hashed_file hf = {f, 1469598103934665603ULL};
  char magic[8];
  uint64_t key;
  int32_t head[4];
  double edge;
  int bad = hf_read(&hf, magic, 1, 8) || hf_read(&hf, &key, 8, 1) ||
            hf_read(&hf, head, 4, 4) || hf_read(&hf, &edge, 8, 1);
  bad = bad || memcmp(magic, MAGIC, 8) != 0 || key != ref->key ||
        head[0] != SS_REFERENCE_VERSION || head[1] != ref->frames || head[2] <= 0 ||
        head[2] > MAX_COUNT || head[3] <= 0 || head[3] > MAX_COUNT || !(edge > 0.0);
  if (!bad) {
    long expect = (long)file_size(head[1], head[2], head[3]);
    bad = fseek(f, 0, SEEK_END) != 0 || ftell(f) != expect ||
          fseek(f, (long)file_size(0, 0, 0) - 8, SEEK_SET) != 0;
  }
  if (!bad) {
    ref->nvert = head[2];
    ref->nface = head[3];
    ref->mean_edge_length = edge;
    size_t nv3 = 3 * (size_t)ref->nvert;
    ref->rest = malloc(sizeof(double) * nv3);
    ref->faces = malloc(sizeof(int) * 3 * (size_t)ref->nface);
    ref->pos = malloc(sizeof(double) * nv3 * (size_t)ref->frames);
    bad = !ref->rest || !ref->faces || !ref->pos || sizeof(int) != 4;
    bad = bad || hf_read(&hf, ref->rest, sizeof(double), nv3) ||
          hf_read(&hf, ref->faces, 4, 3 * (size_t)ref->nface) ||
          hf_read(&hf, ref->pos, sizeof(double), nv3 * (size_t)ref->frames);
    uint64_t stored, computed = hf.h;
    bad = bad || fread(&stored, 8, 1, f) != 1 || stored != computed;
    for (int i = 0; !bad && i < 3 * ref->nface; i++)
      bad = ref->faces[i] < 0 || ref->faces[i] >= ref->nvert;
  }
  fclose(f);
  if (bad) {
    free(ref->rest);
    free(ref->faces);
    free(ref->pos);
    ref->rest = NULL;
    ref->faces = NULL;
    ref->pos = NULL;
    return -1;
  }
  return 0;
}

static int cache_write(const ss_reference *ref, const char *path, char *err, int err_sz) {
  char tmp[4200];
  snprintf(tmp, sizeof tmp, "%s.tmp%ld", path, (long)getpid());
  FILE *f = fopen(tmp, "wb");
  if (!f)
    return ss_fail(err, err_sz, SS_E_IO, "reference: cannot write cache file '%s': %s", tmp,
                   strerror(errno));
  hashed_file hf = {f, 1469598103934665603ULL};
  uint64_t key = ref->key;
  int32_t head[4] = {SS_REFERENCE_VERSION, ref->frames, ref->nvert, ref->nface};
  size_t nv3 = 3 * (size_t)ref->nvert;
  int bad = hf_write(&hf, MAGIC, 1, 8) || hf_write(&hf, &key, 8, 1) ||
            hf_write(&hf, head, 4, 4) || hf_write(&hf, &ref->mean_edge_length, 8, 1) ||
            hf_write(&hf, ref->rest, sizeof(double), nv3) ||
            hf_write(&hf, ref->faces, 4, 3 * (size_t)ref->nface) ||
            hf_write(&hf, ref->pos, sizeof(double), nv3 * (size_t)ref->frames);
  uint64_t sum = hf.h;
  bad = bad || fwrite(&sum, 8, 1, f) != 1;
  bad = (fclose(f) != 0) || bad;
  if (bad || rename(tmp, path) != 0) {
    int e = errno;
    remove(tmp);
    return ss_fail(err, err_sz, SS_E_IO, "reference: cannot write cache file '%s': %s", path,
                   strerror(e));
  }
  return SS_OK;
}

/* ---- computing a reference --------------------------------------------------- */

typedef struct collector {
  ss_reference *ref;
  int nomem;
} collector;

static int collect_frame(void *user, int frame, const ss_sim *sim, const double *body_pos) {
  collector *c = user;
  ss_reference *ref = c->ref;
  if (!ref->pos) {
    ref->nvert = ss_sim_skin_nvert(sim);
    ref->nface = ss_sim_skin_nface(sim);
    ref->rest = malloc(sizeof(double) * 3 * (size_t)ref->nvert);
    ref->faces = malloc(sizeof(int) * 3 * (size_t)ref->nface);
    ref->pos = malloc(sizeof(double) * 3 * (size_t)ref->nvert * (size_t)ref->frames);
    if (!ref->rest || !ref->faces || !ref->pos) {
      c->nomem = 1;
      return 1;
    }
    memcpy(ref->rest, ss_sim_skin_rest(sim), sizeof(double) * 3 * (size_t)ref->nvert);
    memcpy(ref->faces, ss_sim_skin_faces(sim), sizeof(int) * 3 * (size_t)ref->nface);
  }
  if (frame >= 1 && frame <= ref->frames)
    memcpy(ref->pos + 3 * (size_t)ref->nvert * (size_t)(frame - 1), ss_sim_skin_positions(sim),
           sizeof(double) * 3 * (size_t)ref->nvert);
  return 0;
}

int ss_reference_get(ss_reference **out, const ss_body *body, const ss_run_settings *run,
                     const char *cache_dir, ss_progress_fn progress, void *progress_user,
                     char *err, int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "reference: NULL argument");
  *out = NULL;
  const double t0 = ss_now_ms();
  ss_reference *ref = calloc(1, sizeof *ref);
  if (!ref) return ss_fail(err, err_sz, SS_E_NOMEM, "reference: out of memory");
  int status = ss_reference_key(body, run, &ref->key, err, err_sz);
  if (status) {
    free(ref);
    return status;
  }
  ref->frames = run_frames(body, run);
  char path[4096] = "";
  if (cache_dir) {
    cache_path(path, sizeof path, cache_dir, ref->key);
    int got = cache_read(ref, path);
    if (got == 0) {
      ref->cache_hit = 1;
      ref->ms = ss_now_ms() - t0;
      *out = ref;
      return SS_OK;
    }
    ref->cache_rejected = got < 0;
  }
  ss_run_settings rs = ss_reference_settings(run);
  rs.frames = ref->frames;
  rs.inside_every = 0; /* its skin is compared, not measured */
  collector c = {ref, 0};
  status = ss_run_body(body, &rs, collect_frame, &c, progress, progress_user, &ref->stats, err,
                       err_sz);
  if (!status && c.nomem)
    status = ss_fail(err, err_sz, SS_E_NOMEM, "reference: out of memory for %d frames",
                     ref->frames);
  if (!status && ref->stats.frames != ref->frames)
    status = ss_fail(err, err_sz, SS_E_ARG, "reference: stopped after %d of %d frames",
                     ref->stats.frames, ref->frames);
  if (!status) {
    ref->mean_edge_length = ref->stats.mean_edge_length;
    if (cache_dir) status = cache_write(ref, path, err, err_sz);
  }
  if (status) {
    ss_reference_destroy(ref);
    return status;
  }
  ref->ms = ss_now_ms() - t0;
  *out = ref;
  return SS_OK;
}

/* ---- the error --------------------------------------------------------------- */

struct ss_ref_error {
  const ss_reference *ref;
  int nvert;
  int direct;      /* 1: the run's skin is the reference's */
  int *face;       /* (nvert) reference face of each run vertex (not direct) */
  double *uv;      /* (nvert x 2) */
  double sum2;
  long long count;
};

int ss_ref_error_create(ss_ref_error **out, const ss_reference *ref, int nvert,
                        const double *rest, char *err, int err_sz) {
  if (!out || !ref || !rest || nvert <= 0)
    return ss_fail(err, err_sz, SS_E_ARG, "reference error: NULL or empty argument");
  *out = NULL;
  ss_ref_error *e = calloc(1, sizeof *e);
  if (!e) return ss_fail(err, err_sz, SS_E_NOMEM, "reference error: out of memory");
  e->ref = ref;
  e->nvert = nvert;
  e->direct = nvert == ref->nvert &&
              memcmp(rest, ref->rest, sizeof(double) * 3 * (size_t)nvert) == 0;
  if (!e->direct) {
    ss_topo *topo = NULL;
    ss_bvh *bvh = NULL;
    int status = ss_topo_create(&topo, ref->nvert, ref->rest, ref->nface, ref->faces, 0.0, err,
                                err_sz);
    if (!status) status = ss_bvh_create(&bvh, topo);
    e->face = malloc(sizeof(int) * (size_t)nvert);
    e->uv = malloc(sizeof(double) * 2 * (size_t)nvert);
    if (!status && (!e->face || !e->uv)) status = SS_E_NOMEM;
    if (!status) {
      ss_bvh_refit(bvh, ref->rest);
      for (int v = 0; v < nvert; v++)
        ss_bvh_closest(bvh, ref->rest, rest + 3 * v, e->face + v, e->uv + 2 * v);
    }
    ss_bvh_destroy(bvh);
    ss_topo_destroy(topo);
    if (status) {
      ss_ref_error_destroy(e);
      return ss_fail(err, err_sz, status, "reference error: cannot bind the skin (%s)",
                     ss_status_string(status));
    }
  }
  *out = e;
  return SS_OK;
}

void ss_ref_error_destroy(ss_ref_error *e) {
  if (!e) return;
  free(e->face);
  free(e->uv);
  free(e);
}

void ss_ref_error_add(ss_ref_error *e, int frame, const double *pos) {
  const ss_reference *ref = e->ref;
  if (frame < 1 || frame > ref->frames) return;
  const double *r = ref->pos + 3 * (size_t)ref->nvert * (size_t)(frame - 1);
  for (int v = 0; v < e->nvert; v++) {
    double p[3];
    if (e->direct) {
      memcpy(p, r + 3 * v, sizeof p);
    } else {
      const int *fv = ref->faces + 3 * e->face[v];
      const double *a = r + 3 * fv[0], *b = r + 3 * fv[1], *c = r + 3 * fv[2];
      const double u = e->uv[2 * v], w = e->uv[2 * v + 1];
      for (int k = 0; k < 3; k++) p[k] = a[k] + u * (b[k] - a[k]) + w * (c[k] - a[k]);
    }
    for (int k = 0; k < 3; k++) {
      double d = pos[3 * v + k] - p[k];
      e->sum2 += d * d;
    }
    e->count++;
  }
}

double ss_ref_error_value(const ss_ref_error *e) {
  if (!e || e->count == 0 || !(e->ref->mean_edge_length > 0.0)) return 0.0;
  return sqrt(e->sum2 / (double)e->count) / e->ref->mean_edge_length;
}

/* ---- a run against references, two references against each other ------------ */

typedef struct run_errors {
  const ss_reference *const *refs;
  int nref;
  ss_ref_error **e; /* (nref) made at the first frame, from the run's own skin */
  int status;
  char msg[256];
  ss_frame_fn next;
  void *next_user;
} run_errors;

static int errors_on_frame(void *user, int frame, const ss_sim *sim, const double *body_pos) {
  run_errors *r = user;
  for (int k = 0; k < r->nref && !r->status; k++) {
    if (!r->refs[k]) continue;
    if (!r->e[k])
      r->status = ss_ref_error_create(&r->e[k], r->refs[k], ss_sim_skin_nvert(sim),
                                      ss_sim_skin_rest(sim), r->msg, sizeof r->msg);
    if (!r->status) ss_ref_error_add(r->e[k], frame, ss_sim_skin_positions(sim));
  }
  if (r->status) return 1;
  return r->next ? r->next(r->next_user, frame, sim, body_pos) : 0;
}

int ss_run_ref_errors(const ss_body *body, const ss_run_settings *run,
                      const ss_reference *const *refs, int nref, double *errors,
                      ss_frame_fn on_frame, void *frame_user, ss_progress_fn progress,
                      void *progress_user, ss_run_stats *stats, char *err, int err_sz) {
  if (nref < 0 || (nref > 0 && (!refs || !errors)))
    return ss_fail(err, err_sz, SS_E_ARG, "reference error: NULL argument");
  run_errors r = {refs, nref, NULL, 0, "", on_frame, frame_user};
  if (nref > 0) {
    r.e = calloc((size_t)nref, sizeof *r.e);
    if (!r.e) return ss_fail(err, err_sz, SS_E_NOMEM, "reference error: out of memory");
  }
  int status = ss_run_body(body, run, errors_on_frame, &r, progress, progress_user, stats, err,
                           err_sz);
  if (!status && r.status) status = ss_fail(err, err_sz, r.status, "%s", r.msg);
  for (int k = 0; k < nref; k++) {
    errors[k] = ss_ref_error_value(r.e[k]);
    ss_ref_error_destroy(r.e[k]);
  }
  free(r.e);
  return status;
}

double ss_ref_difference(const ss_reference *a, const ss_reference *b) {
  ss_ref_error *e = NULL;
  if (ss_ref_error_create(&e, b, a->nvert, a->rest, NULL, 0)) return NAN;
  for (int f = 1; f <= a->frames; f++)
    ss_ref_error_add(e, f, a->pos + 3 * (size_t)a->nvert * (size_t)(f - 1));
  double v = ss_ref_error_value(e);
  ss_ref_error_destroy(e);
  return v;
}
