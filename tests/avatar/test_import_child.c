/* Every step of assimp on a file's content runs in the limited child
 * (safe_import.c), post-processing included: this test interposes assimp's
 * aiApplyPostProcessing (the executable's definition wins over the shared
 * library's) and counts the calls made by this process, not by the import's
 * child (a fork: its count is its own). A 5M-triangle STL (238 MB) once
 * imported in the child, then had JoinIdenticalVertices applied here without a
 * limit (~2 GB) and assimp crashed when it failed. Asserts: no call here, and
 * the vertices of an STL (three per triangle in the file) come back joined. */
#define _GNU_SOURCE
#include <assimp/cimport.h>
#include <dlfcn.h>
#include <string.h>
#include <unistd.h>

#include "skin_sim/ssa_avatar.h"
#include "ss_test.h"

static int calls_here;
static pid_t test_pid;

const struct aiScene *aiApplyPostProcessing(const struct aiScene *scene, unsigned int flags) {
  typedef const struct aiScene *(*fn)(const struct aiScene *, unsigned int);
  static fn real;
  if (!real) real = (fn)dlsym(RTLD_NEXT, "aiApplyPostProcessing");
  if (getpid() == test_pid) calls_here++;
  return real ? real(scene, flags) : NULL;
}

int main(void) {
  test_pid = getpid();
  char dir[] = "/tmp/ssa_ic_XXXXXX", path[64];
  if (!mkdtemp(dir)) return 1;
  snprintf(path, sizeof path, "%s/grid.stl", dir);
  /* an ASCII STL of a 20 x 20 grid of quads: 800 triangles, 2400 corners, 441 vertices */
  FILE *f = fopen(path, "w");
  if (!f) return 1;
  fprintf(f, "solid grid\n");
  const int g = 20;
  for (int i = 0; i < g; i++)
    for (int j = 0; j < g; j++)
      for (int t = 0; t < 2; t++) {
        double c[3][2] = {{i, j}, {i + 1, j + t}, {i + t, j + 1}};
        if (t) c[1][0] = i + 1, c[1][1] = j + 1, c[2][0] = i, c[2][1] = j + 1;
        fprintf(f, " facet normal 0 0 1\n  outer loop\n");
        for (int k = 0; k < 3; k++) fprintf(f, "   vertex %g %g 0\n", 0.01 * c[k][0], 0.01 * c[k][1]);
        fprintf(f, "  endloop\n endfacet\n");
      }
  fprintf(f, "endsolid grid\n");
  fclose(f);
  ssa_asset *a = NULL;
  char err[512] = "";
  CHECK_MSG(ssa_asset_load(&a, path, NULL, err, sizeof err) == SS_OK, "%s", err);
  if (a) {
    printf("grid.stl: %d vertices, %d triangles; aiApplyPostProcessing called %d times here\n",
           a->nvert, a->nface, calls_here);
    CHECK(a->nface == 2 * g * g);
    CHECK_MSG(a->nvert == (g + 1) * (g + 1), "joined in the child: %d vertices", a->nvert);
  }
  CHECK_MSG(calls_here == 0, "aiApplyPostProcessing called %d times outside the child", calls_here);
  ssa_asset_destroy(a);
  unlink(path);
  rmdir(dir);
  return ss_test_finish("test_import_child");
}
