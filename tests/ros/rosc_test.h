/* rosc for tests: what the ROS test helpers (rosc_echo, skin_probe, overload_probe) call
 * besides include/rosc/rosc.h, which declares only what the nodes use. Built from
 * tests/ros/rosc_test.cpp on the shim's inside (src/rosc/rosc_internal.h): the same
 * guard, the same node, the same handles. Conventions as in rosc.h. */
#ifndef ROSC_TEST_H
#define ROSC_TEST_H

#include "rosc/rosc.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- node and time */
/* Resolves a name ("~x", "x", "/x") with the node's namespace and remappings. */
int rosc_resolve_name(const char *name, char *buf, size_t buf_size);
/* ROS time in seconds (see rosc_now). */
int rosc_now_s(double *out);
/* Wall-clock time (system clock), available before rosc_init too. */
int rosc_wall_now(rosc_time *out);
/* Sleeps for seconds of ROS time (follows /clock with sim time).
 * ROSC_E_SHUTDOWN when the sleep was cut short by shutdown. */
int rosc_sleep(double seconds);
/* Sleeps for seconds of wall-clock time. */
int rosc_wall_sleep(double seconds);

/* ---- parameters */
/* A string parameter of any size, malloc'd (caller frees) and NUL-terminated;
 * *len (may be NULL) is its length. ROSC_E_NOTFOUND if not set, ROSC_E_TYPE if not a
 * string. */
int rosc_param_get_string_alloc(const char *name, char **out, size_t *len);
/* *out = 1 if the parameter is set (any type), else 0. */
int rosc_param_has(const char *name, int *out);
int rosc_param_delete(const char *name);   /* ROSC_OK also when it was not set */

/* ---- topics */
/* The fully resolved topic name (after remapping). */
int rosc_pub_topic(const rosc_pub *pub, char *buf, size_t buf_size);
/* Number of publishers connected now. */
int rosc_sub_num_publishers(const rosc_sub *sub, unsigned *out);
/* Reads buf[0, len) with roscpp's own deserialiser as the generated C++ message of
 * `datatype` and serialises that again: *same = 1 if roscpp took exactly those bytes
 * and gave them back (the C encoder's field table agrees with the .msg). ROSC_E_ROS
 * if roscpp could not read them. */
int rosc_test_reserialize(const char *datatype, const uint8_t *buf, size_t len, int *same);

/* Waits (wall clock, up to timeout_s) until /rosout subscribes to this node's log, so
 * that what it logs next reaches rosout.log: roscpp drops the lines a node logs before
 * that connection is up. ROSC_E_TIMEOUT if it did not come. */
int rosc_test_wait_rosout(double timeout_s);

/* ---- services */
/* Calls the std_srvs/Empty service `name`, waiting up to timeout_s (wall clock) for
 * it to exist. ROSC_OK when the server answered success, ROSC_E_TIMEOUT when it did
 * not appear, ROSC_E_ROS when the call failed. */
int rosc_call_empty(const char *name, double timeout_s);

/* ---- logging (rosc_log_at without the caller's place) */
int rosc_log(int level, const char *fmt, ...) ROSC_PRINTF(2, 3);

#ifdef __cplusplus
}
#endif
#endif
