/* Keeping hostile or broken files away from the libraries that parse them
 * (safe_import.c): checks before a file is opened, and an assimp import that
 * can neither hang nor bloat the process. Internal to the avatar layer. */
#ifndef SKIN_SIM_AVATAR_SAFE_IMPORT_H
#define SKIN_SIM_AVATAR_SAFE_IMPORT_H

#include "skin_sim/ssa_avatar.h"

struct aiScene;
struct aiPropertyStore;

/* Defaults of the limits in ssa_asset_opts (a field <= 0 or NaN takes them). */
#define SSA_MAX_FILE_MB_DEFAULT 256.0
#define SSA_IMPORT_TIMEOUT_S_DEFAULT 60.0
#define SSA_IMPORT_MEM_MB_DEFAULT 4096.0

/* SS_OK if path names a regular file (after symbolic links) of at most
 * max_mb megabytes (<= 0: no cap); else SS_E_IO with one sentence naming
 * `what`, the path and the problem (missing, a FIFO, a directory, a device,
 * too large). Opens nothing: a FIFO is refused without blocking. */
int ssa_check_input_file(const char *path, const char *what, double max_mb, char *err,
                         int err_sz);

/* The checks of a mesh file before assimp reads it: ssa_check_input_file
 * with opts->max_file_mb (default 256 MB), then cheap format checks of the
 * header (OFF, PLY: declared vertex and face counts that the file's size
 * cannot hold). SS_OK or SS_E_IO / SS_E_MESH with one sentence. */
int ssa_check_mesh_file(const char *path, const ssa_asset_opts *opts, char *err, int err_sz);

/* aiImportFileExWithProperties(path, flags, NULL, props), then (a scene whose
 * positions are all finite) aiApplyPostProcessing(scene, post_flags) when
 * post_flags is not 0, all run in a child process limited to
 * opts->import_timeout_s seconds (default 60) and opts->import_mem_mb more
 * megabytes of address space (default 4096); the scene comes back over a pipe
 * (assimp's binary format) and is read again here, with no processing: no
 * step of assimp on the file's content runs without the limits. Returns the
 * scene (release with aiReleaseImport) or NULL with *status SS_E_IO and one
 * sentence in err: assimp's own message, a time-out, running out of memory or
 * a crash of the importer; SS_E_NONFINITE: a position not finite (checked
 * before post-processing, which would merge a NaN vertex into another). */
const struct aiScene *ssa_safe_import(const char *path, unsigned flags, unsigned post_flags,
                                      const struct aiPropertyStore *props,
                                      const ssa_asset_opts *opts, int *status, char *err,
                                      int err_sz);

#endif
