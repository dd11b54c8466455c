/* Internal: union-find over integer ids (path halving), the smaller id the
 * root, so a set's representative is its smallest member: the vertex weld
 * (mesh.c) and the rigid pieces (pieces.c). */
#ifndef SKIN_SIM_UNION_FIND_H
#define SKIN_SIM_UNION_FIND_H

static inline int uf_find(int *parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

static inline void uf_union(int *parent, int a, int b) {
  a = uf_find(parent, a);
  b = uf_find(parent, b);
  if (a < b) parent[b] = a;
  else if (b < a) parent[a] = b;
}

#endif
