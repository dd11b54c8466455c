/* Internal: the URDF as flat arrays, filled by the urdfdom wrapper
 * (urdf_parse.cpp, the only C++ of the avatar layer). Everything is owned by
 * the struct and freed with ssa_urdf_data_free. Links are in urdfdom's map
 * order (by name); joints likewise. Poses are xyz + quaternion (x, y, z, w). */
#ifndef SKIN_SIM_AVATAR_URDF_PARSE_H
#define SKIN_SIM_AVATAR_URDF_PARSE_H

#ifdef __cplusplus
extern "C" {
#endif

enum ssa_urdf_geom { SSA_GEOM_NONE = 0, SSA_GEOM_SPHERE, SSA_GEOM_BOX, SSA_GEOM_CYLINDER, SSA_GEOM_MESH };

typedef struct ssa_urdf_data {
  char *robot_name;
  int root_link;
  int nlink;
  char **link_name;        /* (nlink) */
  int njoint;
  char **joint_name;       /* (njoint) */
  int *joint_type;         /* (njoint) ssa_joint_type */
  int *joint_parent;       /* (njoint) parent link index */
  int *joint_child;        /* (njoint) child link index */
  double *joint_origin;    /* (njoint x 7) xyz, quaternion xyzw */
  double *joint_axis;      /* (njoint x 3) */
  int *joint_has_limits;   /* (njoint) */
  double *joint_lower;     /* (njoint) */
  double *joint_upper;     /* (njoint) */
  char **joint_mimic;      /* (njoint) name of the mimicked joint or NULL */
  double *joint_mimic_mult; /* (njoint) */
  double *joint_mimic_off; /* (njoint) */
  int nvisual;
  int *visual_link;        /* (nvisual) */
  int *visual_geom;        /* (nvisual) ssa_urdf_geom */
  char **visual_uri;       /* (nvisual) mesh filename as written, or NULL */
  double *visual_origin;   /* (nvisual x 7) */
  double *visual_scale;    /* (nvisual x 3) mesh scale */
  double *visual_size;     /* (nvisual x 3) box dims; sphere radius; cylinder radius, length */
} ssa_urdf_data;

/* Parses URDF XML text. Returns 0 and *out, or a negative ss_status with the
 * parser's complaint (one sentence, without the file name) in err. Never throws. */
int ssa_urdf_parse(const char *xml, ssa_urdf_data **out, char *err, int err_sz);
void ssa_urdf_data_free(ssa_urdf_data *d);

#ifdef __cplusplus
}
#endif
#endif
