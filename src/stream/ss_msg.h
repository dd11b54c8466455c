/* skin_sim stream: the few ROS 1 messages the nodes use, as C views, and their
 * encoding in ROS 1's wire format (the node library, src/stream; no ROS headers).
 *
 * The shim (include/rosc/rosc.h) moves serialized bytes only; what the bytes mean is
 * here, described once per message as a table of fields over its view (msg.c), and
 * one encoder and one decoder walk every table. The wire format is ROS 1's: fields in
 * the .msg's order, little-endian, no padding; a string or variable array is a uint32
 * count then its elements; bool is one byte; time is two uint32. The md5sums and
 * definitions the bytes travel under are the generated C++ messages' (the shim's
 * table), so rosbag, rviz and `rostopic echo` see the real types; a field table that
 * drifted from its .msg is caught by test_rosc (bytes against roscpp's own, and
 * rospy's messages read back).
 *
 * A view is a plain struct whose arrays are (pointer, count) pairs; a count counts
 * elements of the message's own array (floats of SkinMesh.positions, points of
 * Marker.points). Decoding copies arrays into a scratch the caller keeps from message
 * to message (wire arrays are not aligned), so steady traffic does not allocate;
 * encoding writes into a buffer the caller keeps, grown only when a message is larger
 * than any before. */
#ifndef SKIN_SIM_SS_MSG_H
#define SKIN_SIM_SS_MSG_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The message types, and their ROS names (ss_msg_datatype). */
enum { SS_MSG_SKIN_MESH, SS_MSG_SKIN_STATS, SS_MSG_JOINT_STATE, SS_MSG_MARKER, SS_MSG_STRING,
       SS_MSG_TYPES };
/* "skin_sim/SkinMesh", ...; NULL for an unknown type. */
const char *ss_msg_datatype(int type);

typedef struct ss_msg_time { uint32_t sec, nsec; } ss_msg_time; /* since 1970 */
static inline int64_t ss_msg_time_to_ns(ss_msg_time t) { return (int64_t)t.sec * 1000000000 + (int64_t)t.nsec; }
static inline ss_msg_time ss_msg_time_from_ns(int64_t ns)
{
  ss_msg_time t;
  if (ns < 0) ns = 0; /* clamped to what fits */
  if (ns > (int64_t)4294967295 * 1000000000 + 999999999) ns = (int64_t)4294967295 * 1000000000 + 999999999;
  t.sec = (uint32_t)(ns / 1000000000);
  t.nsec = (uint32_t)(ns % 1000000000);
  return t;
}

#define SS_MSG_FRAME_ID_MAX 256 /* bytes, with the terminating NUL */

/* std_msgs/Header. seq: roscpp writes its own sequence number into messages sent
 * over TCP, so the value given to publish is not what subscribers see. */
typedef struct ss_msg_header {
  uint32_t seq;
  ss_msg_time stamp;
  char frame_id[SS_MSG_FRAME_ID_MAX]; /* NUL-terminated; a longer one is refused */
} ss_msg_header;

/* skin_sim/SkinMesh: a whole triangle mesh in one frame. */
typedef struct ss_msg_skin_mesh {
  ss_msg_header header;
  uint32_t topology_id;
  const float *positions;     /* (n_positions) = (n_vertices x 3) xyz interleaved, metres */
  size_t n_positions;
  const uint32_t *triangles;  /* (n_triangles) = (n_faces x 3) vertex indices */
  size_t n_triangles;
  const uint32_t *rigid_part; /* (n_rigid_part) = (n_vertices) or none (NULL, 0): see
                                 msg/SkinMesh.msg */
  size_t n_rigid_part;
} ss_msg_skin_mesh;

/* skin_sim/SkinStats: what one skin step did and cost (see msg/SkinStats.msg): its
 * fields after the header, in the message's order, as X(type, name); every one is
 * 4 bytes on the wire. */
#define SS_MSG_SKIN_STATS_FIELDS(X) \
  X(float, total_ms) X(float, walk_ms) X(float, assemble_ms) X(float, solve_ms) \
  X(uint32_t, iterations) X(float, residual) X(uint32_t, substeps) \
  X(uint32_t, anchors_at_boundary) X(uint32_t, anchors_at_crease) X(float, max_slide) \
  X(uint32_t, inputs_rejected) X(uint32_t, inputs_dropped) X(uint32_t, resets) \
  X(uint32_t, inputs_skipped) X(uint32_t, failures) X(float, latency_ms) \
  X(uint32_t, triangles_simulated) X(uint32_t, triangles_carried) \
  X(uint32_t, iterations_per_substep) X(float, step_budget_ms) X(uint32_t, faces_turned) \
  X(uint32_t, vertices_far)
#define SS_MSG_FIELD_(type, name) type name;
typedef struct ss_msg_skin_stats {
  ss_msg_header header;
  SS_MSG_SKIN_STATS_FIELDS(SS_MSG_FIELD_)
} ss_msg_skin_stats;

/* sensor_msgs/JointState. Arrays may be empty (NULL, 0). */
typedef struct ss_msg_joint_state {
  ss_msg_header header;
  const char *const *name; /* (n_name) NUL-terminated joint names */
  size_t n_name;
  const double *position;  /* (n_position) rad or m */
  size_t n_position;
  const double *velocity;  /* (n_velocity) */
  size_t n_velocity;
  const double *effort;    /* (n_effort) */
  size_t n_effort;
} ss_msg_joint_state;

/* visualization_msgs/Marker, all fields. Points travel as float64 in the message;
 * here they are float (the skin's type): float -> double -> float is exact. */
enum {
  SS_MSG_MARKER_ARROW = 0, SS_MSG_MARKER_CUBE = 1, SS_MSG_MARKER_SPHERE = 2,
  SS_MSG_MARKER_CYLINDER = 3, SS_MSG_MARKER_LINE_STRIP = 4, SS_MSG_MARKER_LINE_LIST = 5,
  SS_MSG_MARKER_CUBE_LIST = 6, SS_MSG_MARKER_SPHERE_LIST = 7, SS_MSG_MARKER_POINTS = 8,
  SS_MSG_MARKER_TEXT_VIEW_FACING = 9, SS_MSG_MARKER_MESH_RESOURCE = 10,
  SS_MSG_MARKER_TRIANGLE_LIST = 11
};
enum { SS_MSG_MARKER_ADD = 0, SS_MSG_MARKER_DELETE = 2, SS_MSG_MARKER_DELETEALL = 3 };
#define SS_MSG_MARKER_NS_MAX 256
typedef struct ss_msg_marker {
  ss_msg_header header;
  char ns[SS_MSG_MARKER_NS_MAX]; /* NUL-terminated */
  int32_t id;
  int32_t type;                  /* SS_MSG_MARKER_TRIANGLE_LIST, ... */
  int32_t action;                /* SS_MSG_MARKER_ADD, ... */
  double position[3];            /* pose of the marker frame in header.frame_id */
  double orientation[4];         /* quaternion x y z w; all zero is read by rviz as identity
                                    with a warning: give w = 1 */
  double scale[3];               /* TRIANGLE_LIST: 1 1 1 */
  float color[4];                /* r g b a in [0, 1]; used where colors is empty */
  int32_t lifetime[2];           /* sec, nsec; 0: forever */
  int frame_locked;
  const float *points;           /* (n_points x 3) xyz; TRIANGLE_LIST: 3 per triangle */
  size_t n_points;
  const float *colors;           /* (n_colors x 4) rgba; 0 or one per point */
  size_t n_colors;
  const char *text;              /* NULL means "" */
  const char *mesh_resource;     /* NULL means "" */
  int mesh_use_embedded_materials;
} ss_msg_marker;

/* std_msgs/String. */
typedef struct ss_msg_string {
  const char *data; /* NUL-terminated (a received one with a NUL inside reads shorter) */
} ss_msg_string;

/* Room for a view of any type (a subscriber's decode target). */
typedef union ss_msg_any {
  ss_msg_skin_mesh skin_mesh;
  ss_msg_skin_stats skin_stats;
  ss_msg_joint_state joint_state;
  ss_msg_marker marker;
  ss_msg_string string;
} ss_msg_any;

/* A caller's output buffer (zero-initialise it; ss_msg_buf_free at the end). */
typedef struct ss_msg_buf {
  uint8_t *data;
  size_t len, cap;
} ss_msg_buf;
void ss_msg_buf_free(ss_msg_buf *b);

/* A caller's decoding scratch, one per subscriber (zero-initialise it;
 * ss_msg_scratch_free at the end): the arrays of the last message decoded. */
#define SS_MSG_MAX_ARRAYS 8
typedef struct ss_msg_scratch {
  void *data[SS_MSG_MAX_ARRAYS];
  size_t cap[SS_MSG_MAX_ARRAYS];
} ss_msg_scratch;
void ss_msg_scratch_free(ss_msg_scratch *s);

/* Status codes. */
enum { SS_MSG_OK = 0, SS_MSG_E_INVALID = -1, SS_MSG_E_NOMEM = -2, SS_MSG_E_MALFORMED = -3 };

/* view (the struct of `type`) in ROS 1's wire format into out->data[0, out->len).
 * SS_MSG_E_INVALID (with nothing written) if a pointer is NULL with a non-zero count,
 * a fixed-size string is not terminated in its buffer, or a stamp's nsec is 1e9 or
 * more. */
int ss_msg_encode(int type, const void *view, ss_msg_buf *out);
/* buf[0, len) as message `type` into *view, its arrays in scratch (valid until the next
 * decode with it). SS_MSG_E_MALFORMED, with one sentence in why naming the field, if
 * a length prefix claims more bytes than are left, the bytes end early or run on, a
 * string does not fit its fixed-size field, or a stamp's nsec is 1e9 or more (what the
 * encoder refuses too); nothing is sized from a prefix before it is checked against
 * the bytes left. scratch NULL: only sizes the message (the
 * counts and the fixed-size fields filled in, the variable ones NULL), allocating
 * nothing. */
int ss_msg_decode(int type, const uint8_t *buf, size_t len, void *view, ss_msg_scratch *scratch,
                  char *why, size_t why_size);

#ifdef __cplusplus
}
#endif
#endif
