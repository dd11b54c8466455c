/* Damaged input, deterministically: real files and texts truncated at random
 * places or with random bytes changed, loaded through every loader. Each
 * load either succeeds (and then poses finitely) or fails with a status and
 * a message; nothing crashes. Meant for the AddressSanitizer build. Leaks
 * inside assimp's own importers on broken files are assimp's (5.2.5) and are
 * suppressed; leaks of ours are not. */
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "skin_sim/ssa_avatar.h"
#include "ss_test.h"

/* LeakSanitizer reads this when the test is built with -fsanitize=address. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void) { return "leak:libassimp.so\n"; }

static char dir[] = "/tmp/ssa_fuzz_XXXXXX";
static unsigned long long rng = 0x5eed;

static unsigned rnd(unsigned n) { return (unsigned)(ss_test_rand(&rng) * n) % (n ? n : 1); }

static char *slurp(const char *path, long *n) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  *n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *b = malloc((size_t)*n + 1);
  if (b && fread(b, 1, (size_t)*n, f) != (size_t)*n) {
    free(b);
    b = NULL;
  }
  fclose(f);
  if (b) b[*n] = '\0';
  return b;
}

/* A damaged copy: truncated (odd k) or with a few bytes changed (even k). */
static long damage(const char *src, long n, char *dst, int k) {
  memcpy(dst, src, (size_t)n);
  if (k % 2) return (long)rnd((unsigned)n);
  int flips = 1 + (int)rnd(6);
  for (int i = 0; i < flips; i++) dst[rnd((unsigned)n)] = (char)rnd(256);
  return n;
}

static void write_file(const char *path, const char *data, long n) {
  FILE *f = fopen(path, "wb");
  if (f) {
    fwrite(data, 1, (size_t)n, f);
    fclose(f);
  }
}

static int ok_count = 0, err_count = 0;

static void fuzz_asset(const char *path, int variants) {
  long n = 0;
  char *src = slurp(path, &n);
  if (!src || n == 0) {
    free(src);
    return;
  }
  const char *ext = strrchr(path, '.');
  char out[256];
  snprintf(out, sizeof out, "%s/damaged%s", dir, ext ? ext : "");
  char *buf = malloc((size_t)n + 1);
  for (int k = 0; k < variants; k++) {
    long m = damage(src, n, buf, k);
    write_file(out, buf, m);
    char err[512] = "";
    ssa_avatar *av = NULL;
    int st = ssa_avatar_load_asset(&av, out, NULL, err, sizeof err);
    if (st == SS_OK) {
      ok_count++;
      double *p = malloc(sizeof(double) * 3 * (size_t)av->nvert);
      for (int a = -1; a < av->asset->nanim; a++) {
        CHECK_EQ_INT(ssa_avatar_pose_anim(av, a, 0.37, p), SS_OK);
      }
      free(p);
      ssa_avatar_destroy(av);
    } else {
      err_count++;
      CHECK(st < 0 && err[0] != '\0' && av == NULL);
    }
  }
  free(buf);
  free(src);
}

static void fuzz_text(const char *text, int variants, int kind) {
  long n = (long)strlen(text);
  char *buf = malloc((size_t)n + 1);
  char path[256];
  snprintf(path, sizeof path, "%s/damaged.%s", dir, kind == 0 ? "urdf" : "csv");
  for (int k = 0; k < variants; k++) {
    long m = damage(text, n, buf, k);
    buf[m] = '\0';
    char err[512] = "";
    if (kind == 0) {
      ssa_robot *r = NULL;
      int st = ssa_robot_load_string(&r, buf, NULL, NULL, err, sizeof err);
      if (st == SS_OK) {
        ok_count++;
        double *lw = malloc(sizeof(double) * 16 * (size_t)(r->nlink > 0 ? r->nlink : 1));
        ssa_robot_fk(r, NULL, lw);
        free(lw);
        ssa_robot_destroy(r);
      } else {
        err_count++;
        CHECK(st < 0 && err[0] != '\0' && r == NULL);
      }
    } else {
      write_file(path, buf, m);
      ssa_motion *mo = NULL;
      int st = ssa_motion_read_csv(&mo, path, err, sizeof err);
      if (st == SS_OK) {
        ok_count++;
        ssa_motion_destroy(mo);
      } else {
        err_count++;
        CHECK(st < 0 && strstr(err, "damaged.csv") != NULL && mo == NULL);
      }
    }
  }
  free(buf);
}

int main(void) {
  if (!mkdtemp(dir)) return 1;
  fuzz_text(ssa_mannequin_urdf(), 300, 0);
  fuzz_text("time,a,b\n0,1,2\n0.5,1.5,2.5\n1,2,3\n", 300, 1);
  char p[1024];
  snprintf(p, sizeof p, "%s/data/gltf-khronos-skinned/RiggedSimple/glTF-Binary/RiggedSimple.glb",
           SS_SHARED_DIR);
  fuzz_asset(p, 60);
  snprintf(p, sizeof p, "%s/data/gltf-khronos-skinned/SimpleSkin/glTF-Embedded/SimpleSkin.gltf",
           SS_SHARED_DIR);
  fuzz_asset(p, 60);
  fuzz_asset("/usr/share/assimp/models/X/anim_test.x", 40);
  printf("damaged inputs: %d loaded, %d refused with a message, none crashed\n", ok_count,
         err_count);
  ss_test_remove_dir(dir);
  return ss_test_finish("test_fuzz");
}
