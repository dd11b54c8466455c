/* skin_sim lab (src/lab, not installed): procedural scenes where anchor methods fail.
 *
 * Each scene is a body mesh generated in code at any resolution plus a scripted
 * motion: the body's positions at any (fractional) frame. Frames are 1/fps
 * seconds apart. A scene's motion is defined for any frame >= 0 (it clamps or
 * loops past its default length). */
#ifndef SKIN_SIM_SS_SCENE_H
#define SKIN_SIM_SS_SCENE_H

#include "skin_sim/ss_common.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ss_scene ss_scene;

/* The built-in scenes, in a fixed order. */
int ss_scene_count(void);
const char *ss_scene_name(int index);   /* NULL out of range */
const char *ss_scene_about(int index);  /* one line: what it stresses */

/* Creates scene `name` with about `tris` triangles (0: the scene's default).
 * Unknown names and absurd sizes give SS_E_ARG with a message. */
int ss_scene_create(ss_scene **out, const char *name, int tris, char *err, int err_sz);
void ss_scene_destroy(ss_scene *scene);

const char *ss_scene_get_name(const ss_scene *scene);
int ss_scene_nvert(const ss_scene *scene);
int ss_scene_nface(const ss_scene *scene);
const int *ss_scene_faces(const ss_scene *scene);        /* (nface x 3) */
const double *ss_scene_rest(const ss_scene *scene);      /* (nvert x 3) rest pose = frame 0 */
int ss_scene_default_frames(const ss_scene *scene);
double ss_scene_fps(const ss_scene *scene);               /* frames per second (30) */
/* Body positions at frame `frame` (fractional frames interpolate the motion,
 * for substeps) into pos (nvert x 3). Allocates nothing. */
void ss_scene_pose(const ss_scene *scene, double frame, double *pos);
/* The pose of frame `frame` a fraction w of the way back to rest (0: that
 * frame's pose, 1: rest) in the motion's own joint angles and offsets, so
 * that the body keeps its shape on the way (a blend of the positions would
 * shrink a bent part towards its axis); the twist's spin goes back the short
 * way. Allocates nothing. */
void ss_scene_pose_toward_rest(const ss_scene *scene, double frame, double w, double *pos);

#ifdef __cplusplus
}
#endif
#endif
