/* Hostile files kept out before assimp sees them (doc/library.md, "Files from users").
 *
 * A mesh file is what a user or a robot_description names, so it may be
 * anything: a FIFO (opening it blocks for ever), a directory, a device, a
 * file of gigabytes, or a few hundred bytes that make assimp allocate 16 GB,
 * loop for ever or read out of bounds (e.g. Debian's own
 * /usr/share/assimp/models/invalid/OutOfMemory.off). Three layers:
 *
 *  1. ssa_check_input_file: stat() before any open; only regular files, and
 *     at most a size cap (mesh files: 256 MB by default).
 *  2. ssa_check_mesh_file: cheap header checks where a format declares its
 *     counts (OFF, PLY): counts that the file's size cannot hold are refused.
 *  3. ssa_safe_import: the import itself runs in a child process (fork) with
 *     a wall-clock limit (the parent kills it) and an address-space limit
 *     (setrlimit RLIMIT_AS: what the process had plus the allowance, so it
 *     works under AddressSanitizer's large reservations too). The child hands
 *     the scene back over a pipe in assimp's own binary format (assbin),
 *     which the parent reads again from memory. Whatever assimp does in the
 *     child -- hang, allocate without bound, crash -- the caller gets one
 *     error, and its own memory is untouched. */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdint.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <assimp/cexport.h>
#include <assimp/cimport.h>
#include <assimp/scene.h>

#include "safe_import.h"
#include "ssa_util.h"

static double pick(double v, double def) { return v > 0.0 ? v : def; }

int ssa_check_input_file(const char *path, const char *what, double max_mb, char *err,
                         int err_sz) {
  if (!path || !path[0]) return ss_fail(err, err_sz, SS_E_IO, "no %s given", what);
  struct stat sb;
  if (stat(path, &sb) != 0)
    return ss_fail(err, err_sz, SS_E_IO, "%s '%s' cannot be opened: %s", what, path, strerror(errno));
  if (!S_ISREG(sb.st_mode)) {
    const char *kind = S_ISDIR(sb.st_mode)    ? "a directory"
                       : S_ISFIFO(sb.st_mode) ? "a FIFO (named pipe)"
                       : S_ISCHR(sb.st_mode)  ? "a character device"
                       : S_ISBLK(sb.st_mode)  ? "a block device"
                       : S_ISSOCK(sb.st_mode) ? "a socket"
                                              : "not a regular file";
    return ss_fail(err, err_sz, SS_E_IO, "%s '%s' is %s, not a regular file: refused", what, path,
                   kind);
  }
  if (max_mb > 0.0 && (double)sb.st_size > max_mb * 1048576.0)
    return ss_fail(err, err_sz, SS_E_IO, "%s '%s' is %.3g MB, over the cap of %g MB: refused", what,
                   path, (double)sb.st_size / 1048576.0, max_mb);
  return SS_OK;
}

/* ---------------------------------------------------------------- header checks */

/* Next token of the header text at *p (skipping blanks and # comments). */
static int next_token(const char **p, const char *end, char *tok, size_t tok_sz) {
  const char *s = *p;
  for (;;) {
    while (s < end && (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n')) s++;
    if (s < end && *s == '#') {
      while (s < end && *s != '\n') s++;
      continue;
    }
    break;
  }
  size_t n = 0;
  while (s < end && !(*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n')) {
    if (n + 1 < tok_sz) tok[n++] = *s;
    s++;
  }
  tok[n] = '\0';
  *p = s;
  return n > 0;
}

/* A count as written: digits only, saturating (a huge count stays huge). */
static int parse_count(const char *tok, double *out) {
  if (!tok[0]) return 0;
  double v = 0.0;
  for (const char *c = tok; *c; c++) {
    if (*c < '0' || *c > '9') return 0;
    v = v * 10.0 + (*c - '0');
  }
  *out = v;
  return 1;
}

/* ASCII OFF: "[ST][C][N][4][n]OFF", then vertex, face and edge counts. The
 * smallest vertex line is "0 0 0\n" (6 bytes), the smallest face "3 0 1 2\n" (8). */
static int check_off(const char *path, const char *head, size_t n, double size, char *err,
                     int err_sz) {
  const char *p = head, *end = head + n;
  char tok[64];
  if (!next_token(&p, end, tok, sizeof tok)) return SS_OK;
  size_t tl = strlen(tok);
  if (tl < 3 || strcmp(tok + tl - 3, "OFF") != 0) return SS_OK; /* assimp will say */
  const char *save = p;
  if (next_token(&p, end, tok, sizeof tok) && strcmp(tok, "BINARY") == 0) return SS_OK;
  p = save;
  double nv = 0, nf = 0;
  if (!next_token(&p, end, tok, sizeof tok) || !parse_count(tok, &nv)) return SS_OK;
  if (!next_token(&p, end, tok, sizeof tok) || !parse_count(tok, &nf)) return SS_OK;
  if (6.0 * nv + 8.0 * nf > size)
    return ss_fail(err, err_sz, SS_E_MESH,
                   "mesh file '%s' declares %.0f vertices and %.0f faces (OFF header), more than "
                   "its %.0f bytes can hold: refused",
                   path, nv, nf, size);
  return SS_OK;
}

/* PLY: every "element NAME COUNT" needs at least one byte per property per
 * instance (binary) or two (ASCII: a digit and a separator). */
static int check_ply(const char *path, const char *head, size_t n, double size, char *err,
                     int err_sz) {
  const char *p = head, *end = head + n;
  char tok[64];
  if (!next_token(&p, end, tok, sizeof tok) || strcmp(tok, "ply") != 0) return SS_OK;
  double need = 0.0, count = 0.0, per = 1.0;
  int nprop = 0, in_element = 0;
  while (next_token(&p, end, tok, sizeof tok)) {
    if (strcmp(tok, "format") == 0) {
      if (next_token(&p, end, tok, sizeof tok)) per = strcmp(tok, "ascii") == 0 ? 2.0 : 1.0;
    } else if (strcmp(tok, "element") == 0) {
      if (in_element) need += count * (nprop > 0 ? nprop : 1) * per;
      char name[64];
      in_element = next_token(&p, end, name, sizeof name) && next_token(&p, end, tok, sizeof tok) &&
                   parse_count(tok, &count);
      nprop = 0;
    } else if (strcmp(tok, "property") == 0) {
      nprop++;
    } else if (strcmp(tok, "end_header") == 0) {
      break;
    }
  }
  if (in_element) need += count * (nprop > 0 ? nprop : 1) * per;
  if (need > size)
    return ss_fail(err, err_sz, SS_E_MESH,
                   "mesh file '%s' declares elements needing at least %.0f bytes (PLY header), "
                   "more than its %.0f bytes: refused",
                   path, need, size);
  return SS_OK;
}

int ssa_check_mesh_file(const char *path, const ssa_asset_opts *opts, char *err, int err_sz) {
  double max_mb = opts ? opts->max_file_mb : 0.0;
  if (!(max_mb < 0.0)) max_mb = pick(max_mb, SSA_MAX_FILE_MB_DEFAULT); /* negative: no cap */
  int st = ssa_check_input_file(path, "mesh file", max_mb, err, err_sz);
  if (st != SS_OK) return st;
  int is_off = ssa_has_ext(path, ".off"), is_ply = ssa_has_ext(path, ".ply");
  if (!is_off && !is_ply) return SS_OK;
  int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0)
    return ss_fail(err, err_sz, SS_E_IO, "mesh file '%s' cannot be opened: %s", path, strerror(errno));
  struct stat sb;
  char head[4096];
  ssize_t n = 0;
  if (fstat(fd, &sb) == 0 && S_ISREG(sb.st_mode)) n = read(fd, head, sizeof head - 1);
  close(fd);
  if (n <= 0) return SS_OK; /* empty: assimp says so */
  head[n] = '\0';
  return is_off ? check_off(path, head, (size_t)n, (double)sb.st_size, err, err_sz)
                : check_ply(path, head, (size_t)n, (double)sb.st_size, err, err_sz);
}

/* ---------------------------------------------------------------- the import in a child */

/* The child's message: one byte (0 scene, 2 scene with the scene's metadata
 * on its root node, 1 assimp's error), 8 bytes of
 * length (host order), then the payload. */
static int write_all(int fd, const void *buf, size_t n) {
  const char *p = buf;
  while (n > 0) {
    ssize_t w = write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return -1;
    p += w;
    n -= (size_t)w;
  }
  return 0;
}

static void child_send(int fd, unsigned char kind, const void *data, uint64_t n) {
  unsigned char hdr[9];
  hdr[0] = kind;
  memcpy(hdr + 1, &n, 8);
  if (write_all(fd, hdr, sizeof hdr) != 0 || write_all(fd, data, (size_t)n) != 0) _exit(3);
}

/* Bytes of address space the process has mapped now (0 if unknown). */
static double current_vsize(void) {
  FILE *f = fopen("/proc/self/statm", "r");
  if (!f) return 0.0;
  unsigned long pages = 0;
  int ok = fscanf(f, "%lu", &pages) == 1;
  fclose(f);
  return ok ? (double)pages * (double)sysconf(_SC_PAGESIZE) : 0.0;
}

static void child_import(int fd, const char *path, unsigned flags, unsigned post_flags,
                         const struct aiPropertyStore *props, double as_bytes, double timeout_s) {
  /* The host's handlers (a crash reporter, a fuzzer's, the sanitizers') are
   * not the child's business: a crash or a limit ends it with its signal. */
  static const int sigs[] = {SIGPIPE, SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL, SIGINT,
                             SIGTERM, SIGXCPU, SIGXFSZ, SIGALRM, SIGUSR1, SIGUSR2};
  for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) signal(sigs[i], SIG_DFL);
  /* the parent gives the one error: nothing of the child's own on the terminal
   * (e.g. "terminate called after throwing std::bad_alloc" at the memory limit) */
  int devnull = open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (devnull >= 0) {
    dup2(devnull, STDERR_FILENO);
    dup2(devnull, STDOUT_FILENO);
    close(devnull);
  }
  struct rlimit rl;
  rl.rlim_cur = rl.rlim_max = 0;
  setrlimit(RLIMIT_CORE, &rl);
  if (as_bytes > 0.0 && as_bytes < 9e18) {
    rl.rlim_cur = rl.rlim_max = (rlim_t)as_bytes;
    setrlimit(RLIMIT_AS, &rl);
  }
  rl.rlim_cur = rl.rlim_max = (rlim_t)(timeout_s + 2.0); /* CPU seconds, behind the parent's clock */
  setrlimit(RLIMIT_CPU, &rl);
  const struct aiScene *sc = aiImportFileExWithProperties(path, flags, NULL, props);
  if (!sc) {
    const char *why = aiGetErrorString();
    if (!why || !why[0]) why = "unknown format or broken file";
    child_send(fd, 1, why, strlen(why));
    _exit(0);
  }
  /* every position finite (message kind 3), then the post-processing, here
   * under the limits too (a 5M-triangle STL's JoinIdenticalVertices took ~2 GB) */
  for (unsigned m = 0; m < sc->mNumMeshes; m++) {
    const struct aiMesh *me = sc->mMeshes[m];
    for (unsigned i = 0; i < me->mNumVertices; i++)
      if (!isfinite(me->mVertices[i].x) || !isfinite(me->mVertices[i].y) ||
          !isfinite(me->mVertices[i].z)) {
        char why[1200];
        snprintf(why, sizeof why, "vertex %u of mesh %u ('%.1024s') is not finite", i, m,
                 me->mName.data);
        child_send(fd, 3, why, strlen(why));
        _exit(0);
      }
  }
  if (post_flags && !(sc = aiApplyPostProcessing(sc, post_flags))) { /* assimp released it */
    const char *why = aiGetErrorString();
    if (!why || !why[0]) why = "post-processing failed";
    child_send(fd, 1, why, strlen(why));
    _exit(0);
  }
  /* assbin keeps node metadata but not the scene's (FBX: UnitScaleFactor,
   * UpAxis): carried on the root node when that has none, and put back there
   * by the parent (message kind 2). */
  unsigned char kind = 0;
  if (sc->mMetaData && sc->mRootNode && !sc->mRootNode->mMetaData) {
    sc->mRootNode->mMetaData = sc->mMetaData;
    kind = 2;
  }
  const struct aiExportDataBlob *blob = aiExportSceneToBlob(sc, "assbin", 0);
  if (!blob) {
    const char *why = "the imported scene could not be handed back (assbin export failed)";
    child_send(fd, 1, why, strlen(why));
    _exit(0);
  }
  child_send(fd, kind, blob->data, (uint64_t)blob->size);
  _exit(0); /* no atexit handlers, no stdio flush of the parent's buffers */
}

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Reads n bytes before the deadline: 0 ok, 1 end of file, 2 timeout, 3 error. */
static int read_until(int fd, void *buf, size_t n, double deadline) {
  char *p = buf;
  while (n > 0) {
    double left = deadline - now_s();
    if (left <= 0.0) return 2;
    struct pollfd pf = {fd, POLLIN, 0};
    int r = poll(&pf, 1, (int)(left * 1000.0) + 1);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) return 3;
    if (r == 0) continue;
    ssize_t got = read(fd, p, n);
    if (got < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (got < 0) return 3;
    if (got == 0) return 1;
    p += got;
    n -= (size_t)got;
  }
  return 0;
}

const struct aiScene *ssa_safe_import(const char *path, unsigned flags, unsigned post_flags,
                                      const struct aiPropertyStore *props,
                                      const ssa_asset_opts *opts, int *status, char *err,
                                      int err_sz) {
  double timeout_s = pick(opts ? opts->import_timeout_s : 0.0, SSA_IMPORT_TIMEOUT_S_DEFAULT);
  double mem_mb = pick(opts ? opts->import_mem_mb : 0.0, SSA_IMPORT_MEM_MB_DEFAULT);
  *status = SS_E_IO;
  int fds[2];
  if (pipe(fds) != 0) {
    ss_fail(err, err_sz, SS_E_IO, "mesh file '%s' cannot be imported: no pipe (%s)", path,
            strerror(errno));
    return NULL;
  }
  double as_bytes = current_vsize() + mem_mb * 1048576.0;
  fflush(NULL);
  pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    ss_fail(err, err_sz, SS_E_IO, "mesh file '%s' cannot be imported: fork failed (%s)", path,
            strerror(errno));
    return NULL;
  }
  if (pid == 0) {
    close(fds[0]);
    child_import(fds[1], path, flags, post_flags, props, as_bytes, timeout_s);
    _exit(3);
  }
  close(fds[1]);
  double deadline = now_s() + timeout_s;
  unsigned char hdr[9];
  uint64_t len = 0;
  char *buf = NULL;
  int r = read_until(fds[0], hdr, sizeof hdr, deadline);
  if (r == 0) {
    memcpy(&len, hdr + 1, 8);
    if ((double)len > mem_mb * 1048576.0 || !(buf = malloc((size_t)len + 1)))
      r = 3;
    else
      r = read_until(fds[0], buf, (size_t)len, deadline);
  }
  close(fds[0]);
  if (r == 2) kill(pid, SIGKILL);
  int wst = 0;
  pid_t w;
  do w = waitpid(pid, &wst, 0);
  while (w < 0 && errno == EINTR);
  if (r == 2) {
    free(buf);
    ss_fail(err, err_sz, SS_E_IO,
            "mesh file '%s' cannot be imported: the import took longer than %g s and was stopped",
            path, timeout_s);
    return NULL;
  }
  if (r != 0) {
    free(buf);
    if (w == pid && WIFSIGNALED(wst)) {
      int sig = WTERMSIG(wst);
      ss_fail(err, err_sz, SS_E_IO,
              "mesh file '%s' cannot be imported: the importer %s (signal %d, %s; memory limit "
              "%g MB)",
              path, sig == SIGXCPU ? "ran out of CPU time" : sig == SIGSEGV || sig == SIGBUS ? "crashed" : "died",
              sig, strsignal(sig), mem_mb);
    } else {
      ss_fail(err, err_sz, SS_E_IO,
              "mesh file '%s' cannot be imported: the importer ended without a scene (out of "
              "memory within the %g MB limit, or a broken file)",
              path, mem_mb);
    }
    return NULL;
  }
  if (hdr[0] == 1 || hdr[0] == 3) {
    buf[len] = '\0';
    size_t n = strlen(buf);
    while (n > 0 && (buf[n - 1] == '\n' || buf[n - 1] == '.' || buf[n - 1] == ' ')) buf[--n] = '\0';
    if (hdr[0] == 3)
      *status = ss_fail(err, err_sz, SS_E_NONFINITE, "mesh file '%s': %s", path, buf);
    else
      ss_fail(err, err_sz, SS_E_IO, "mesh file '%s' cannot be imported: %s", path, buf);
    free(buf);
    return NULL;
  }
  const struct aiScene *sc =
      len <= UINT_MAX ? aiImportFileFromMemory(buf, (unsigned)len, 0, "assbin") : NULL;
  free(buf);
  if (!sc) {
    const char *why = aiGetErrorString();
    ss_fail(err, err_sz, SS_E_IO, "mesh file '%s' cannot be imported: the scene handed back "
            "could not be read (%s)", path, why && why[0] ? why : "assbin");
    return NULL;
  }
  if (hdr[0] == 2 && sc->mRootNode) {
    /* the scene's metadata back in place; the reader's own (the format's
     * name, assbin) goes to the root node, where assimp frees it */
    struct aiScene *msc = (struct aiScene *)sc;
    struct aiMetadata *mine = msc->mMetaData;
    msc->mMetaData = msc->mRootNode->mMetaData;
    msc->mRootNode->mMetaData = mine;
  }
  *status = SS_OK;
  return sc;
}
