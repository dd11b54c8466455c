/* skin_sim_node's output (skin_node.h): skin_mesh in the published layout, skin_stats,
 * and skin_marker, a shaded TRIANGLE_LIST coloured by ~marker_color. */
#include "skin_node.h"

static void publish_marker(node *nd, const ss_msg_header *hdr);

void node_publish(node *nd, const ss_msg_header *in_hdr, const ss_sim_stats *acc, double total_ms,
                  int substeps)
{
  /* the input's stamp; its frame unless ~frame_id names another (two skins told apart) */
  ss_msg_header own = *in_hdr;
  if (nd->p.frame_id[0]) snprintf(own.frame_id, sizeof own.frame_id, "%s", nd->p.frame_id);
  if (nd->p.tf_prefix[0]) {
    const char *pre = nd->p.tf_prefix + (nd->p.tf_prefix[0] == '/');
    const char *f = own.frame_id[0] == '/' ? own.frame_id + 1 : own.frame_id;
    char joined[SS_MSG_FRAME_ID_MAX];
    size_t lp = strlen(pre), lf = strlen(f), k = 0;
    for (size_t i = 0; i < lp && k + 1 < sizeof joined; i++) joined[k++] = pre[i];
    if (lp && pre[lp - 1] != '/' && k + 1 < sizeof joined) joined[k++] = '/';
    for (size_t i = 0; i < lf && k + 1 < sizeof joined; i++) joined[k++] = f[i];
    joined[k] = '\0';
    memcpy(own.frame_id, joined, sizeof joined);
  }
  const ss_msg_header *hdr = &own;
  /* in the body's layout: every seam copy from its welded skin vertex */
  const double *x = ss_sim_skin_positions(nd->sim);
  size_t n3 = 3 * (size_t)nd->nvert;
  /* every seam copy from its welded skin vertex; a rigid piece's as received */
  for (int v = 0; v < nd->nvert; v++) {
    const double *src = nd->carried[v] ? nd->body + 3 * (size_t)v : x + 3 * (size_t)nd->vert_weld[v];
    for (int d = 0; d < 3; d++) nd->pos_out[3 * (size_t)v + d] = (float)src[d];
  }
  ss_msg_skin_mesh out;
  memset(&out, 0, sizeof out);
  out.header = *hdr;
  out.topology_id = nd->skin.weld ? nd->skin.topology_id : nd->topology_id;
  out.positions = nd->pos_out;
  out.n_positions = n3;
  out.triangles = nd->tri_out;
  out.n_triangles = 3 * (size_t)nd->nface;
  if (msg_publish(nd->pub_mesh, SS_MSG_SKIN_MESH, &out) == ROSC_OK) nd->frames_out++;

  double max_slide =
      ss_input_slide(nd->nanchor, ss_sim_anchor_faces(nd->sim), ss_sim_anchor_uv(nd->sim),
                     nd->face0, nd->uv0, nd->body, nd->nbvert, nd->bfaces, nd->nbface, nd->slide);
  ss_msg_skin_stats s;
  memset(&s, 0, sizeof s);
  s.header = *hdr;
  s.total_ms = (float)total_ms;
  s.walk_ms = (float)acc->walk_ms;
  s.assemble_ms = (float)acc->assemble_ms;
  s.solve_ms = (float)(acc->factor_ms + acc->solve_ms);
  s.iterations = (uint32_t)acc->iterations;
  s.residual = (float)acc->residual;
  s.substeps = (uint32_t)substeps;
  s.anchors_at_boundary = (uint32_t)acc->anchors_boundary;
  s.anchors_at_crease = (uint32_t)acc->anchors_crease;
  s.max_slide = (float)max_slide;
  s.inputs_rejected = nd->rejected;
  s.inputs_dropped = nd->dropped + (uint32_t)nd->stream.lost;
  s.resets = nd->resets;
  s.inputs_skipped = nd->skipped;
  s.failures = nd->failures;
  rosc_time now_ros;
  if (rosc_now(&now_ros) == ROSC_OK)
    s.latency_ms = (float)(1e-6 * (double)(rosc_time_to_ns(now_ros) - ss_msg_time_to_ns(hdr->stamp)));
  s.triangles_simulated = (uint32_t)nd->nface_sim;
  s.triangles_carried = (uint32_t)nd->nface_carried;
  s.iterations_per_substep = (uint32_t)nd->budget.iterations;
  s.step_budget_ms = (float)nd->budget_ms;
  s.faces_turned = (uint32_t)nd->faces_turned;
  s.vertices_far = (uint32_t)nd->vertices_far;
  msg_publish(nd->pub_stats, SS_MSG_SKIN_STATS, &s);

  if (nd->p.marker_rate == 0.0) return;
  double now = 0;
  rosc_wall_now_s(&now);
  if (nd->p.marker_rate > 0.0 && now - nd->last_marker_wall < 1.0 / nd->p.marker_rate) return;
  unsigned nsub = 0;
  rosc_pub_num_subscribers(nd->pub_marker->pub, &nsub);
  if (nsub == 0) return;
  nd->last_marker_wall = now;
  publish_marker(nd, hdr);
}

/* skin_marker: the skin as a TRIANGLE_LIST in the body's layout, a colour per corner.
 * Colours are made per skin (welded) vertex, so every seam copy gets its vertex's:
 * ~marker_color's colour times a light term from the vertex's normal (rviz draws the
 * marker unlit; without it the skin is a flat silhouette). */
static void publish_marker(node *nd, const ss_msg_header *hdr)
{
  int nw = nd->nweld;
  if (!nd->mk_vcol) { /* once per skin; freed with it (free_sim) */
    nd->mk_vcol = malloc(4 * (size_t)nw * sizeof(float));
    nd->mk_work = malloc(3 * (size_t)nw * sizeof(double));
    if (!nd->mk_vcol || !nd->mk_work) {
      free(nd->mk_vcol); free(nd->mk_work);
      nd->mk_vcol = NULL; nd->mk_work = NULL;
      NODE_ERROR_THROTTLE(5.0, "out of memory for skin_marker's colours (%d vertices)", nw);
      return;
    }
  }
  const double *x = ss_sim_skin_positions(nd->sim);
  const int *skin_faces = ss_sim_skin_faces(nd->sim); /* the body's faces, welded */
  float *vc = nd->mk_vcol;
  if (nd->p.marker_color == MARKER_STRETCH) {
    double *ratio = nd->mk_work + 2 * (size_t)nw; /* the last third; area sums the first two */
    ss_input_vertex_area_ratio(nw, x, ss_sim_skin_rest(nd->sim), nd->nface, skin_faces,
                               nd->mk_work, ratio);
    for (int w = 0; w < nw; w++) ss_input_stretch_color(ratio[w], vc + 4 * (size_t)w);
  } else {
    for (int w = 0; w < nw; w++) {
      float *c = vc + 4 * (size_t)w;
      if (nd->p.marker_color == MARKER_ONE) {
        c[0] = nd->p.marker_rgb[0]; c[1] = nd->p.marker_rgb[1]; c[2] = nd->p.marker_rgb[2];
        c[3] = 1.0f;
      } else { /* vertex anchors come first: anchor w belongs to skin vertex w */
        ss_input_slide_color(nd->slide[w], nd->p.slide_scale, c);
      }
    }
  }
  ss_input_shade(nw, x, nd->nface, skin_faces, nd->mk_work, vc);
  for (int f = 0; f < nd->nface; f++) {
    for (int k = 0; k < 3; k++) {
      int v = nd->faces[3 * f + k];
      size_t c = 3 * (size_t)f + (size_t)k;
      for (int d = 0; d < 3; d++) nd->mk_pts[3 * c + d] = nd->pos_out[3 * (size_t)v + d];
      memcpy(nd->mk_col + 4 * c, vc + 4 * (size_t)nd->vert_weld[v], 4 * sizeof(float));
    }
  }
  /* what rviz needs of a TRIANGLE_LIST: action ADD (0), identity orientation (all
   * zero draws with a warning), unit scale, opaque white; colours come per point */
  ss_msg_marker mk;
  memset(&mk, 0, sizeof mk);
  mk.type = SS_MSG_MARKER_TRIANGLE_LIST;
  mk.orientation[3] = 1.0;
  mk.scale[0] = mk.scale[1] = mk.scale[2] = 1.0;
  mk.color[0] = mk.color[1] = mk.color[2] = mk.color[3] = 1.0f;
  mk.header = *hdr;
  snprintf(mk.ns, sizeof mk.ns, "skin");
  mk.id = 0;
  mk.points = nd->mk_pts;
  mk.n_points = 3 * (size_t)nd->nface;
  mk.colors = nd->mk_col;
  mk.n_colors = 3 * (size_t)nd->nface;
  msg_publish(nd->pub_marker, SS_MSG_MARKER, &mk);
}
