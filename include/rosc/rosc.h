/* rosc: a thin C API over ROS 1's roscpp for skin_sim's plain-C nodes.
 *
 * The only code in skin_sim that includes ROS headers lives behind this header
 * (src/rosc, C++14). It knows nothing about skins, nor about the fields of a
 * message: it moves serialized messages, as roscpp does on the wire, and is glue
 * only (as robot_state_publisher's main is). It declares what the nodes call; what
 * only the tests call (name lookups, service calls, parameter deletion) is in
 * tests/ros/rosc_test.h, built on the same inside.
 *
 * Why bytes, and not typed C views converted field by field in C++: a typed shim
 * copies every message type a second time (a C struct plus a conversion each way
 * per field) and grows with each type. Bytes need one generic path: a publisher
 * takes the bytes a node encoded, a subscriber hands over the bytes it received,
 * under the md5sum, definition and name of the generated C++ message (one table row
 * per type, from ros::message_traits), so the topic is indistinguishable from a
 * roscpp node's for rosbag, rviz and rostopic. The encoding lives in pure C beside
 * the checks that must see the bytes anyway (a subscriber sizes a message before
 * anything is allocated for it: roscpp's deserialiser trusts length prefixes), with
 * no allocation per message beyond the caller's reused buffers. Services go the same
 * way (a request's bytes in, a response's out), so dynamic_reconfigure is the nodes'
 * too. The cost is that the C field tables must follow the .msg files: test_rosc has
 * roscpp read the C encoder's bytes back unchanged and reads rospy's messages.
 *
 * Conventions
 * - Every function that can fail returns an int status: ROSC_OK (0) or a negative
 *   ROSC_E_* code; rosc_strerror() names it. No C++ exception ever crosses this API.
 * - Outputs go through pointer arguments; on error they are left unchanged unless
 *   the function says otherwise (parameter getters always fill in the default).
 * - Names follow ROS: "~x" is private to the node, "/x" global, "x" relative to the
 *   node's namespace. Give topics relative names so users can remap them
 *   (`mesh_in:=/body/mesh` on the command line or <remap> in a launch file).
 * - Threading: call everything from one thread (the one that spins); callbacks run
 *   in that thread inside rosc_spin_*. Logging is safe from any thread. (A rosc_diag
 *   publishes from a thread of its own while the spinning one is busy: rosc_diag_busy.)
 * - Messages are serialized bytes (see "messages" below); a subscriber callback's
 *   bytes are valid only during the callback.
 */
#ifndef ROSC_ROSC_H
#define ROSC_ROSC_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__)
#define ROSC_PRINTF(fmt_idx, first_arg) __attribute__((format(printf, fmt_idx, first_arg)))
#else
#define ROSC_PRINTF(fmt_idx, first_arg)
#endif

/* ------------------------------------------------------------------ status codes */
enum {
  ROSC_OK = 0,
  ROSC_E_INVALID = -1,   /* bad argument: NULL, unterminated string, wrong message type */
  ROSC_E_STATE = -2,     /* not initialised, initialised twice, or already shut down */
  ROSC_E_ROS = -3,       /* roscpp raised an error (its text went to the log) */
  ROSC_E_NOMEM = -4,     /* out of memory */
  ROSC_E_TYPE = -5,      /* parameter is set but has another type; default returned */
  ROSC_E_TRUNCATED = -6, /* output buffer too small; the output holds a prefix */
  ROSC_E_TIMEOUT = -7,   /* the master did not answer in time */
  ROSC_E_NOTFOUND = -8,  /* a required parameter is not set */
  ROSC_E_SHUTDOWN = -9   /* interrupted because the node is shutting down */
};
/* A short constant English text for a status code (never NULL). */
const char *rosc_strerror(int status);

/* ------------------------------------------------------------------ node life */
enum {
  ROSC_INIT_ANONYMOUS = 1u << 0,      /* append a unique suffix to the node name */
  ROSC_INIT_NO_SIGINT = 1u << 1,      /* do not install roscpp's SIGINT handler */
  ROSC_INIT_NO_ROSOUT = 1u << 2       /* do not send log messages to /rosout */
};
/* Initialises roscpp and starts the node. Consumes ROS arguments from argv
 * (remappings `a:=b`, `_param:=value`, `__name:=`, `__ns:=`) and updates *argc,
 * so the caller parses only its own options afterwards. `node_name` is the default
 * name (no slashes). The node needs the master (ROS_MASTER_URI): with
 * master_timeout_s >= 0, rosc_init waits that long (wall clock) for it and returns
 * ROSC_E_TIMEOUT if it does not answer (calling rosc_init again waits again); with
 * master_timeout_s < 0 it waits for ever, as roscpp nodes do. ROSC_E_STATE once the
 * node has started (one node per process). */
int rosc_init(int *argc, char **argv, const char *node_name, unsigned options,
              double master_timeout_s);
/* 1 while the node runs; 0 before rosc_init, after rosc_shutdown, after SIGINT (with
 * roscpp's handler) or when another node with the same name took over. */
int rosc_ok(void);
/* Stops the node: unregisters every publisher and subscriber, closes connections.
 * Handles stay valid to destroy. Called automatically at exit if forgotten. */
int rosc_shutdown(void);
/* The fully resolved node name (e.g. "/skin_sim"), copied into buf. */
int rosc_node_name(char *buf, size_t buf_size);

/* ------------------------------------------------------------------ spinning */
/* Runs the callbacks that are ready, waiting up to timeout_s seconds (wall clock)
 * for the first one if none is (0: do not wait). */
int rosc_spin_once(double timeout_s);
/* Runs callbacks until duration_s seconds (wall clock) have passed or the node stops;
 * duration_s < 0 spins until the node stops. ROSC_OK when the time ran out,
 * ROSC_E_SHUTDOWN when it returned because the node stopped. */
int rosc_spin_for(double duration_s);

/* ------------------------------------------------------------------ time */
typedef struct rosc_time { uint32_t sec, nsec; } rosc_time;       /* since 1970 */

static inline double rosc_time_to_s(rosc_time t) { return (double)t.sec + 1e-9 * (double)t.nsec; }
static inline int64_t rosc_time_to_ns(rosc_time t) { return (int64_t)t.sec * 1000000000 + (int64_t)t.nsec; }

/* ROS time: simulated (/clock) when the parameter /use_sim_time is true, else wall.
 * With sim time it is zero until the first /clock message arrives. */
int rosc_now(rosc_time *out);
/* Wall-clock time (system clock) in seconds, available before rosc_init too. */
int rosc_wall_now_s(double *out);

/* A loop rate in ROS time. rosc_rate_sleep sleeps for what is left of the cycle;
 * *met (may be NULL) is 1 if the cycle was on time, 0 if it overran. */
typedef struct rosc_rate rosc_rate;
int rosc_rate_create(rosc_rate **out, double hz);
int rosc_rate_sleep(rosc_rate *rate, int *met);
int rosc_rate_reset(rosc_rate *rate);
int rosc_rate_destroy(rosc_rate *rate);   /* NULL is fine */

/* ------------------------------------------------------------------ parameters */
/* Getters: name is "~x" (private), "/x" (global) or "x" (relative). *out always
 * receives either the server's value or the default; *was_set (may be NULL) says
 * which. Not set: ROSC_OK with the default. Set with another type: ROSC_E_TYPE with
 * the default (a double getter accepts an int; an int getter accepts a double with
 * no fractional part). Strings: ROSC_E_TRUNCATED if the value does not fit (buf then
 * holds a terminated prefix; *was_set is 1). `def` may be NULL for "". */
int rosc_param_get_string(const char *name, char *buf, size_t buf_size, const char *def,
                          int *was_set);
int rosc_param_get_double(const char *name, double *out, double def, int *was_set);
int rosc_param_get_int(const char *name, int *out, int def, int *was_set);
int rosc_param_get_bool(const char *name, int *out, int def, int *was_set);
/* The type the server holds under name (ROSC_PARAM_*), for a node to say why a
 * getter returned ROSC_E_TYPE. ROSC_E_NOTFOUND if it is not set. */
enum { ROSC_PARAM_STRING = 1, ROSC_PARAM_INT, ROSC_PARAM_DOUBLE, ROSC_PARAM_BOOL, ROSC_PARAM_LIST,
       ROSC_PARAM_DICT, ROSC_PARAM_OTHER };
int rosc_param_type(const char *name, int *type);
/* The URDF as robot_state_publisher finds it: the parameter "robot_description"
 * searched upwards from the node's namespace (so "/robot_description" for a node in
 * the root namespace; remappable). Any size; malloc'd, caller frees. ROSC_E_NOTFOUND
 * if no such parameter exists. */
int rosc_robot_description(char **out, size_t *len);
/* Setters; bool is any non-zero int. */
int rosc_param_set_string(const char *name, const char *value);
int rosc_param_set_double(const char *name, double value);
int rosc_param_set_int(const char *name, int value);
int rosc_param_set_bool(const char *name, int value);

/* ------------------------------------------------------------------ messages */
/* Messages travel as ROS 1's serialized bytes (the wire format, without the 4-byte
 * length that precedes a message on a connection). A type is named as ROS names it
 * ("skin_sim/SkinMesh"); the shim knows, from the generated C++ messages, the md5sum,
 * the definition and the name of each it serves (ROSC_MSG_TYPES), so that rosbag,
 * rviz and `rostopic echo` see the real types. It knows no field: the nodes encode
 * and decode the bytes themselves (src/stream/ss_msg.h, pure C). */
#define ROSC_MSG_TYPES "skin_sim/SkinMesh skin_sim/SkinStats sensor_msgs/JointState " \
                       "visualization_msgs/Marker std_msgs/String dynamic_reconfigure/Config " \
                       "dynamic_reconfigure/ConfigDescription"

/* ------------------------------------------------------------------ publishers */
typedef struct rosc_pub rosc_pub;
/* Advertises `topic` (give it relative) for messages of `datatype` (one of
 * ROSC_MSG_TYPES; others are ROSC_E_INVALID). queue_size: outgoing messages kept per
 * subscriber before the oldest is dropped (>= 1). latch: new subscribers get the last
 * message. */
int rosc_pub_create(rosc_pub **out, const char *datatype, const char *topic,
                    unsigned queue_size, int latch);
/* Publishes one message of the publisher's type: its len serialized bytes (copied
 * before it returns; ROSC_E_INVALID for NULL with len > 0 or len >= 4 GiB). */
int rosc_publish(rosc_pub *pub, const uint8_t *bytes, size_t len);
/* Number of subscribers connected now. */
int rosc_pub_num_subscribers(const rosc_pub *pub, unsigned *out);
int rosc_pub_destroy(rosc_pub *pub);   /* unadvertises; NULL is fine */

/* ------------------------------------------------------------------ subscribers */
typedef struct rosc_sub rosc_sub;
/* A received message's len serialized bytes, valid during the call only. Nothing has
 * been read from them: a node that takes input from outside sizes them before it
 * trusts a length prefix (src/stream/ss_msg.h does). */
typedef void (*rosc_msg_cb)(const uint8_t *buf, size_t len, void *user);
/* Subscribes `topic` (give it relative) for messages of `datatype` (one of
 * ROSC_MSG_TYPES); cb(bytes, len, user) runs inside rosc_spin_*. queue_size: incoming
 * messages kept before the oldest is dropped (>= 1); a node that must not fall behind
 * uses 1; a message dropped so is never copied. TCP_NODELAY is requested (low
 * latency). */
int rosc_subscribe(rosc_sub **out, const char *datatype, const char *topic,
                   unsigned queue_size, rosc_msg_cb cb, void *user);
/* The fully resolved topic name (after remapping), for the node's log lines. */
int rosc_sub_topic(const rosc_sub *sub, char *buf, size_t buf_size);
int rosc_sub_destroy(rosc_sub *sub);   /* unsubscribes; NULL is fine */

/* ------------------------------------------------------------------ services */
/* Services served as bytes, like topics: a request's serialized bytes in, a response's
 * out, under the md5sum and names of the generated C++ service of srv_type (one of
 * ROSC_SRV_TYPES). cb runs inside rosc_spin_*, in the spinning thread like every
 * callback; it returns 0 for success with *resp, *resp_len the response's bytes (valid
 * until its next call; NULL, 0 for an empty response), anything else makes the call
 * fail (the caller sees a service error). Names as topics ("~reset" is private). */
#define ROSC_SRV_TYPES "std_srvs/Empty dynamic_reconfigure/Reconfigure"
typedef struct rosc_srv rosc_srv;
typedef int (*rosc_srv_cb)(const uint8_t *req, size_t req_len, const uint8_t **resp,
                           size_t *resp_len, void *user);
int rosc_srv_create(rosc_srv **out, const char *name, const char *srv_type, rosc_srv_cb cb,
                    void *user);
/* A std_srvs/Empty service: cb(user) returns 0 for success. */
typedef int (*rosc_empty_cb)(void *user);
int rosc_srv_empty(rosc_srv **out, const char *name, rosc_empty_cb cb, void *user);
/* The fully resolved service name. */
int rosc_srv_name(const rosc_srv *srv, char *buf, size_t buf_size);
int rosc_srv_destroy(rosc_srv *srv);   /* unadvertises; NULL is fine */

/* ------------------------------------------------------------------ diagnostics */
/* Health on /diagnostics (diagnostic_msgs/DiagnosticArray) through
 * diagnostic_updater: one status named "<node name>: <task>" for hardware_id.
 * The node decides the level and the figures; rosc only publishes them. */
enum { ROSC_DIAG_OK = 0, ROSC_DIAG_WARN = 1, ROSC_DIAG_ERROR = 2, ROSC_DIAG_STALE = 3 };
typedef struct rosc_diag rosc_diag;
typedef struct rosc_kv { const char *key, *value; } rosc_kv;
int rosc_diag_create(rosc_diag **out, const char *hardware_id, const char *task);
/* The publishing period in seconds: the private parameter ~diagnostic_period of
 * diagnostic_updater (default 1 s), read again at every update. */
int rosc_diag_period(rosc_diag *d, double *out);
/* Publishes the status now: level (ROSC_DIAG_*), a one-line message and n key/value
 * pairs (kv may be NULL with n 0; NULL keys or values are ROSC_E_INVALID). */
int rosc_diag_update(rosc_diag *d, int level, const char *message, const rosc_kv *kv, size_t n);
/* The status published in place of the last one while the spinning thread is busy:
 * level (ROSC_DIAG_*), message, and one more key/value pair (key "" for none). */
typedef struct rosc_diag_busy_status {
  int level;
  char message[256], key[64], value[64];
} rosc_diag_busy_status;
/* Called from the handle's own thread: the status to publish after busy_s seconds of
 * work, the last status published at last_level. It must read nothing the spinning
 * thread writes meanwhile (what it needs, the node sets before rosc_diag_busy). */
typedef void (*rosc_diag_busy_cb)(double busy_s, int last_level, rosc_diag_busy_status *out,
                                  void *user);
/* Marks the start (cb non-NULL) or the end (cb NULL) of one long piece of work in the
 * spinning thread. While it lasts, a thread of the handle's own publishes, every
 * diagnostic period without a rosc_diag_update, the last status's key/value pairs
 * with what cb(busy_s, last_level, out, user) gives, so that /diagnostics does not go
 * silent while one step takes long. The node decides what it says. */
int rosc_diag_busy(rosc_diag *d, rosc_diag_busy_cb cb, void *user);
int rosc_diag_destroy(rosc_diag *d);   /* NULL is fine */

/* ------------------------------------------------------------------ logging */
/* Levels as rosconsole's. Messages go to the console and, once the node runs, to
 * /rosout (logger "ros.skin_sim"); the level threshold is rosconsole's (DEBUG is
 * hidden by default). Safe from any thread and before rosc_init. */
enum { ROSC_LOG_DEBUG = 0, ROSC_LOG_INFO = 1, ROSC_LOG_WARN = 2, ROSC_LOG_ERROR = 3,
       ROSC_LOG_FATAL = 4 };
/* The caller's file, line and function show in the log; the macros below fill them
 * in. No throttle here: a node throttles (and counts what it held back) below the shim
 * (src/stream/ss_throttle.h, src/nodes/node_log.h) and hands rosc the finished line. */
int rosc_log_at(int level, const char *file, int line, const char *func, const char *fmt, ...)
    ROSC_PRINTF(5, 6);

#define ROSC_DEBUG(...) rosc_log_at(ROSC_LOG_DEBUG, __FILE__, __LINE__, __func__, __VA_ARGS__)
#define ROSC_INFO(...) rosc_log_at(ROSC_LOG_INFO, __FILE__, __LINE__, __func__, __VA_ARGS__)
#define ROSC_WARN(...) rosc_log_at(ROSC_LOG_WARN, __FILE__, __LINE__, __func__, __VA_ARGS__)
#define ROSC_ERROR(...) rosc_log_at(ROSC_LOG_ERROR, __FILE__, __LINE__, __func__, __VA_ARGS__)

#ifdef __cplusplus
}
#endif
#endif /* ROSC_ROSC_H */
