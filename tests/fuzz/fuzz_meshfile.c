/* libFuzzer harness: mesh files through the avatar loader (ssa_avatar_load_asset:
 * the checks of safe_import.c, assimp's import in its child process, the
 * scene read back, our scene walk, welding and weights), then one pose. The
 * first byte picks the file's extension (OFF, PLY, OBJ, STL, SMD, X, 3DS,
 * glTF, Collada, ...), the rest is the file. Whatever the bytes make assimp
 * do in the child -- fail, hang, allocate without bound, crash -- this
 * process must get SS_OK with a finite body or one error with a message. */
#include <assert.h>
#include <unistd.h>

#include "fuzz_util.h"
#include "skin_sim/ssa_avatar.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void) { return "leak:libassimp.so\n"; }

static const char *const exts[] = {".off", ".ply", ".obj", ".stl", ".smd", ".x", ".3ds",
                                   ".gltf", ".dae", ".ase", ".md5mesh", ".fbx", ".glb", ".nff"};

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size < 1) return 0;
  char dir[] = "/tmp/ss_fuzz_mesh_XXXXXX";
  if (!mkdtemp(dir)) return 0;
  char path[64];
  snprintf(path, sizeof path, "%s/body%s", dir, exts[data[0] % (sizeof exts / sizeof exts[0])]);
  FILE *f = fopen(path, "wb");
  if (!f) abort();
  fwrite(data + 1, 1, size - 1, f);
  fclose(f);
  ssa_avatar_opts o = ssa_avatar_default_opts();
  o.asset.import_timeout_s = 5.0;
  o.asset.import_mem_mb = 1024.0;
  ssa_avatar *av = NULL;
  char err[512] = "";
  int st = ssa_avatar_load_asset(&av, path, &o, err, sizeof err);
  if (st != SS_OK) {
    assert(av == NULL && err[0] != '\0');
  } else {
    assert(av && av->nvert > 0 && av->nface > 0);
    double *pos = malloc(3 * (size_t)av->nvert * sizeof(double));
    if (ssa_avatar_pose_anim(av, 0, 0.5, pos) == SS_OK)
      for (int i = 0; i < 3 * av->nvert; i++) assert(isfinite(pos[i]));
    free(pos);
    ssa_avatar_destroy(av);
  }
  unlink(path);
  rmdir(dir);
  return 0;
}
