/* The weld of ss_topo_create (mesh.c), for the tests that count its work. */
#ifndef SKIN_SIM_MESH_WELD_H
#define SKIN_SIM_MESH_WELD_H

/* Fills vert_weld (nvert: caller vertex -> welded id, ids dense in order of
 * first appearance; vertices within tol of each other, transitively, share
 * one) and returns the number of welded ids, or -1 out of memory. *ncompare
 * (may be NULL): the distance tests made, about nvert times the vertices in a
 * cell of side tol and its neighbours, whatever the orientation. */
int ss_weld_ids(int nvert, const double *pos, double tol, int *vert_weld, long long *ncompare);

#endif
