/* Internal: a destructor's arrays freed in one statement.
 *
 *   SS_FREE_ALL(g->adj, g->dist, g->seen, g);
 *
 * frees each pointer in the order written (NULL ones are no-ops, as for
 * free), so a half-built object is freed by its destructor too. */
#ifndef SKIN_SIM_SS_FREE_H
#define SKIN_SIM_SS_FREE_H

#include <stddef.h>
#include <stdlib.h>

static inline void ss_free_list(void *const *ptr, size_t n) {
  for (size_t i = 0; i < n; i++) free(ptr[i]);
}

#define SS_FREE_ALL(...) \
  ss_free_list((void *const[]){__VA_ARGS__}, sizeof((void *const[]){__VA_ARGS__}) / sizeof(void *))

#endif
