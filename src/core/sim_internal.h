/* Internal: the inside of ss_sim, shared by its modules. Read one step in
 * sim.c, top to bottom; the rest:
 *
 *   sim.c            ss_sim_step and its four stages in order; reset, state, live settings,
 *                    accessors
 *   sim_anchor.c     stage 4, the anchor pass (slide, walk, tether); anchor positions
 *   sim_energy.c     E(x), its gradient, Hessian assembly over all terms; the line search's
 *                    first trial asked of the terms
 *   orient.c         the orient term (faces face up, vertices not under the body)
 *   solver.c         the one solver loop (solver.h); line_search.c its line search
 *   solver_newton.c  projected Newton directions with CHOLMOD (3n x 3n)
 *   solver_qn.c      L-BFGS on the constant L (x) I3 matrix (scalar n x n CHOLMOD)
 *   sim_threads.c    threads 0: the probe choosing the next step's thread count
 *   sim_model.c      the model's and the data's arenas, building a model alone, derived
 *                    materials, create / destroy, sims sharing a model
 *   model.h          the model and the files that build it (model_*.c), which know no sim
 *
 * The model (fixed once built, shareable) and the data of a run: see "model
 * and data" below. Arrays are flat with their shape in the field lists. Unknowns ("dofs") are the free skin
 * vertices in increasing vertex order; dof vector entry 3k + c is coordinate c
 * of free vertex dof_vert[k]. */
#ifndef SKIN_SIM_SIM_INTERNAL_H
#define SKIN_SIM_SIM_INTERNAL_H

#include "model.h"
#include "mover.h"
#include "par.h"
#include "skin_sim/ss_sim.h"

/* ---- model and data (MuJoCo's mjModel / mjData split) ----------------------
 *
 * The MODEL of a skin on a body is everything fixed once it is built:
 * topology, rest data, masses and springs, hinges, the sparsity pattern,
 * the packed energy layout and the symbolic analysis of the solver's matrix
 * (below, "symbolic analysis"). Several sims may run on one model (a reference
 * or truth run, a second skin of the same body: ss_sim_create_from_model);
 * it is built alone (model.h, sim_model.c) and nothing writes it afterwards: a sim
 * holds it as `const ss_model *`, and a new material (ss_sim_set_settings)
 * is a new model that borrows the old one's structure (`shape`).
 * The DATA of a run (struct ss_sim) is the state, the anchors, the solver
 * workspaces and the step's counters.
 *
 * Each holds its arrays in ONE arena (one allocation, 64-byte aligned
 * slices) laid out from ONE list of fields below: name, element type, count
 * (elements allocated, evaluated with `m` the model and `sim` the sim), and
 * shape. The list declares the fields, sizes the arena and places them;
 * nothing else allocates, checks or frees them. The model's counts that are
 * only known while it is built (dofs, hinges, blocks of the pattern) are
 * allocated at bounds known before: nvert for dofs, nhinge_max for hinges.
 * Not in the arenas: the body topology (ss_topo), the mover, the walker
 * objects (their pointers are) and the CHOLMOD objects, each with its own
 * create and destroy. */

/* The data of a run: counts of the built model `m` and of the sim's own
 * settings (solver, history) and threads. */
#define SS_DATA_ARRAYS(X)                                                                        \
  X(x, double, 3 * (size_t)m->nvert, "(nvert x 3) skin positions")                               \
  X(x_prev, double, 3 * (size_t)m->nvert, "(nvert x 3) at the start of the substep")             \
  X(v, double, 3 * (size_t)m->nvert, "(nvert x 3) velocities")                                   \
  X(xfull_t, double, 3 * (size_t)m->nvert, "(nvert x 3) trial positions (fixed in place)")       \
  X(body_prev, double, 3 * (size_t)m->nbvert, "(nbvert x 3) body pose at the end of the last step") \
  X(body_sub, double, 3 * (size_t)m->nbvert, "(nbvert x 3) body pose of the current substep")    \
  X(anchor_face, int, (size_t)m->nanchor, "(nanchor)")                                           \
  X(anchor_uv, double, 2 * (size_t)m->nanchor, "(nanchor x 2)")                                  \
  X(anchor_pos, double, 3 * (size_t)m->nanchor, "(nanchor x 3) in the current substep pose")     \
  X(anchor_pull, double, (size_t)m->nanchor,                                                     \
    "(nanchor) sum over the last step's substeps of |a* - a0|")                                  \
  X(anchor_path, double, (size_t)m->nanchor, "(nanchor) sum of the lengths walked (walk only)")  \
  X(walkers, ss_walker *, (size_t)sim->nthread_max, "(nthread_max) walk scratch, one per thread") \
  X(face_energy, double, (size_t)m->nface, "(nsimface) per simulated face, in one evaluation: membrane and barycenter spring") \
  X(orient_s, double, (size_t)m->nface, "(nsimface) orient.c: s of each judged face in one evaluation") \
  X(face_grad, double, (sim->nthread_max > 1 ? 9 : 3) * (size_t)m->nsimface + 1,                 \
    "their gradients (9 per simulated face; only on threads) or area vectors (3)")               \
  X(mi, double, (size_t)m->ndof, "(ndof) inertia weight: mass (1/h^2 + damping/h)")              \
  X(target, double, 3 * (size_t)m->ndof, "(ndof x 3) inertia target (prediction, damping, gravity)") \
  X(xd, double, 3 * (size_t)m->ndof, "(ndof x 3) solver: the unknowns")                          \
  X(gd, double, 3 * (size_t)m->ndof, "(ndof x 3) solver: gradient at xd")                        \
  X(dir, double, 3 * (size_t)m->ndof, "(ndof x 3) solver: search direction")                     \
  X(xt, double, 3 * (size_t)m->ndof, "(ndof x 3) solver: trial point")                           \
  X(gt, double, 3 * (size_t)m->ndof, "(ndof x 3) solver: gradient at the trial point")           \
  X(guess, double, 3 * (size_t)m->ndof, "(ndof x 3) anchors of free vertices in the previous pose") \
  X(h_const, double, sim->set.solver == SS_SOLVER_NEWTON ? (size_t)m->nnz3 : 0,                  \
    "(nnz of H) Newton: inertia + springs")                                                      \
  X(lb_s, double, SS_SIM_QN_HISTORY(sim) * 3 * (size_t)m->ndof, "(m x ndof x 3) L-BFGS s ring") \
  X(lb_y, double, SS_SIM_QN_HISTORY(sim) * 3 * (size_t)m->ndof, "(m x ndof x 3) L-BFGS y ring") \
  X(lb_rho, double, SS_SIM_QN_HISTORY(sim), "(m)")                                               \
  X(lb_alpha, double, SS_SIM_QN_HISTORY(sim), "(m)")                                               \
  X(skin_n, double, 3 * (size_t)m->ndof, "(ndof x 3) unit skin normal at the start of the solve (0: none)") \
  X(par_part, double,                                                                            \
    SS_PAR_SUMS * (size_t)ss_par_nblocks(3 * m->nvert > m->nface ? 3 * m->nvert : m->nface) + 1,   \
    "par.h: the blocks' partial sums of one pass")                                               \
  X(depth_line, double, 3 * (size_t)m->ndof,                                                    \
    "(ndof x 3) orient.c: the depth springs in reach of a full step, each block's (par.h) packed " \
    "from its first dof on: depth, rate along the search direction, stiffness (0: the end)")     \
  X(orient_n, double, 4 * ((size_t)m->nface + m->nvert), "orient.c: per simface n, face_c (0: not judged); per dof at 4 nface n, judged")
#define SS_SIM_QN_HISTORY(sim) \
  ((sim)->set.solver == SS_SOLVER_QUASI_NEWTON ? (size_t)(sim)->set.lbfgs_history : 0)

struct ss_sim {
  const ss_model *m;          /* the model this sim runs on (counted in m->refs): read only */
  ss_sim_settings set;        /* this sim's; face_mask points to m->mask (or NULL) */
  void *arena;                /* every array of SS_DATA_ARRAYS */
  size_t arena_bytes;
  ss_mover *mover;            /* body frames and BVH in the current pose */
  struct ss_collider *collider; /* contact scratch (collide.c) */
  int nthread;                /* threads the current step uses (OpenMP; 1 without it) */
  int nthread_max;            /* threads made at create (walkers, team) */
  int isa;                    /* vector instruction set of the kernels (isa.h): the widest the
                                 CPU runs, chosen at create (ss_sim_set_isa); the same bits
                                 from any */
  int thread_probe;           /* threads 0: steps into the current probe period (-1: off) */
  int probe_period;           /* threads 0: steps in the current probe period */
  double probe_ms[2];         /* threads 0: step times with nthread_max and with 1 thread */
  int measure_anchors;        /* ss_sim_measure_anchors: anchor_pull and anchor_path summed */
  /* CHOLMOD */
  cholmod_common cc;
  int cc_started;
  /* Newton: 3n x 3n */
  cholmod_sparse *H;
  cholmod_factor *LH;
  double h_const_h;           /* h for which h_const was built (0: none) */
  cholmod_dense *nb, *nx, *ny, *ne; /* rhs, solution, workspaces (3n x 1) */
  /* quasi-Newton: n x n, applied to 3 right-hand sides */
  cholmod_sparse *A;
  cholmod_factor *LA;
  double a_h;                 /* h of the current factorisation of A (0: none) */
  cholmod_dense *qb, *qx, *qy, *qe; /* (n x 3) */
  /* quasi-Newton on threads: the x and y columns of each solve on one thread
   * (cc, qx_xy, qy_xy, qe_xy) while z is solved on another with its own
   * cholmod_common (cc_z, qx_z, qy_z, qe_z); the factor is shared read-only.
   * Made at create where the sim has threads (solver_qn.c) */
  cholmod_common cc_z;
  int cc_z_started;
  cholmod_dense *qx_xy, *qy_xy, *qe_xy, *qx_z, *qy_z, *qe_z;
  int lb_m;                   /* L-BFGS history size */
  int lb_count, lb_head;
  /* over the sim's life (ss_sim_warnings) */
  long long nstep;
  ss_warning warning[SS_NWARNING];
  SS_DATA_ARRAYS(SS_ARENA_FIELD)
};

/* ---- a substep (sim.c): its inputs, one value every stage reads ---- */
typedef struct ss_substep {
  const double *body_pos; /* the body pose at the end of the step */
  double w;               /* share of the way from body_prev to body_pos */
  int first;              /* the first substep of the step */
  int last;               /* the last substep: exactly body_pos */
  double h;               /* its length */
  double slide_frac;      /* share of the way to its skin point an anchor goes */
  double tether_frac;     /* share of the way back home it walks */
} ss_substep;

/* ---- sim_anchor.c: the anchor pass and the anchors' positions ---- */
/* anchor_pos from the anchors and the mover's frames of `pose` (the pose it
 * holds); an anchor without a face follows its body vertex. */
void ss_sim_anchor_positions_update(ss_sim *sim, const double *pose);
/* Stage 4 of a substep: anchors slide towards their skin points, then walk
 * home on the tether; counts into st. */
void ss_sim_move_anchors(ss_sim *sim, const ss_substep *in, ss_sim_stats *st);
/* Each anchor's pull and path back to 0 (ss_sim_measure_anchors). */
void ss_sim_clear_anchor_measures(ss_sim *sim);

/* Moves sim onto a model derived from its own with the material (model
 * settings) of set (sim_model.c, model_derive); its data stay. */
int ss_sim_rematerial(ss_sim *sim, const ss_sim_settings *set, char *err, int err_sz);
/* threads 0: the probe's steps (sim_threads.c). After each step of step_ms
 * wall-clock ms, sets the thread count of the next. */
#define SS_PROBE_STEPS 3       /* steps on one thread, then at most as many on all */
#define SS_PROBE_PERIOD 50     /* steps from one probe to the next while all threads pay */
#define SS_PROBE_PERIOD_MAX 1600 /* the longest period, after probes one thread won */
void ss_sim_choose_threads(ss_sim *sim, double step_ms);
/* Sets the vector instruction set of the sim's kernels (isa.h; one the CPU
 * runs): the same bits from any. Chosen at create: the widest. */
void ss_sim_set_isa(ss_sim *sim, int isa);
/* sim->collider made if it is not (sim_model.c); SS_E_NOMEM. */
int ss_sim_collider_ensure(ss_sim *sim);

/* ---- orient.c: skin faces resist turning over against the body ---- */
/* The unit body normal skin face f is judged against, in the pose of fr;
 * 0 where the face is not judged (see orient.c). */
int ss_sim_orient_normal(const ss_sim *sim, const ss_frames *fr, int f, double n[3]);
/* The normals of the faces and free vertices in the current pose and anchors
 * (orient_n), which energy and Hessian read: after every move of either
 * (ss_sim_energy_begin calls it). */
void ss_sim_orient_begin(ss_sim *sim);
/* Energy at xfull; adds its gradient into g (dofs) if g. 0 when settings orient is 0.
 * s_ready: orient_s already holds every simulated face's s at xfull (the
 * membrane's batch computes them, ss_membrane_eval_batch_orient_isa). */
double ss_sim_orient_energy(const ss_sim *sim, const double *xfull, double *g, int s_ready);
/* The first trial step of a quasi-Newton line search along dir from the
 * unknowns xd, where E's slope is `slope` (< 0): the minimum over (0, 1] of
 * the depth springs along the line (exact: one-sided quadratics) plus a
 * quadratic model of every other term whose minimum is the full step (what
 * the constant preconditioner gets right). 1 where no depth spring is in
 * reach or the model does not apply (see orient.c). Writes depth_line. */
double ss_sim_orient_line_step(ss_sim *sim, const double *xd, const double *dir, double slope);
/* Adds its (Gauss-Newton, PSD) Hessian to the 3n x 3n upper-triangular values. */
void ss_sim_orient_hessian(const ss_sim *sim, const double *xfull, double *vals);

/* ---- sim_energy.c ---- */
/* Sets up the inertia weights and targets of a substep of length h from
 * x_prev, v and the settings. */
void ss_sim_energy_begin(ss_sim *sim, double h);
/* Scatters dofs xd into the full positions xfull (fixed vertices untouched). */
void ss_sim_scatter(const ss_sim *sim, const double *xd, double *xfull);
/* E at the full positions xfull; gradient over dofs into g (may be NULL).
 * Returns NaN/Inf if anything is non-finite. */
double ss_sim_energy(const ss_sim *sim, const double *xfull, double *g);
/* Convergence measure of a dof gradient: max over free vertices of the size
 * of a Jacobi step in mean edge lengths (see settings tol), the gradient
 * along the skin divided by D_v, the diagonal of the scalar matrix (inertia
 * + springs + rest membrane stiffness), and across it (skin_n, set by
 * ss_sim_normals_begin) by inertia + springs alone (sim_energy.c). */
double ss_sim_residual(const ss_sim *sim, const double *g);
/* The same judged by the scalar matrix's diagonal in every direction (the
 * stiffness along the skin): how far from converged the membrane itself is. */
double ss_sim_residual_along(const ss_sim *sim, const double *g);
/* The same measure as a root mean square over free vertices. */
double ss_sim_residual_rms(const ss_sim *sim, const double *g);
/* Adds the Hessian of membrane and hinges at xfull to the values vals of the
 * 3n x 3n upper-triangular matrix H: each element's projected to PSD, or with
 * exact != 0 the membrane's exact (possibly indefinite) Hessian except on
 * nearly collapsed faces (hinges keep their Gauss-Newton Hessian). */
void ss_sim_add_elastic_hessian(const ss_sim *sim, const double *xfull, double *vals, int exact);
/* Values of the constant part (inertia + springs) of H, for the current h. */
void ss_sim_constant_hessian(const ss_sim *sim, double *vals);
/* The skin's unit vertex normals (skin_n) at the full positions xfull, at
 * the start of each solve: the direction across the membrane, in which only
 * inertia and the anchor springs hold a flat skin (ss_sim_residual). */
void ss_sim_normals_begin(ss_sim *sim, const double *xfull);
/* The same with the sim's inertia weights of the current substep. */
void ss_sim_scalar_matrix(const ss_sim *sim, double *vals);

/* ---- solvers (solver.h: the one loop, line search and the solvers' hooks).
 * ss_solver_solve minimises E from xd (in/out, dofs) with the solver of the
 * settings; returns SS_OK or SS_E_SOLVER and fills stats (iterations,
 * residual, residual_rms, ...). *nonfinite is 1 if E was not finite at the
 * start (xd unusable), 2 if only trial points were (xd is the last finite
 * iterate). ---- */
int ss_solver_create(ss_sim *sim, char *err, int err_sz);
int ss_solver_solve(ss_sim *sim, const ss_substep *in, ss_sim_stats *st, double *xd, int *converged,
                    int *stalled, int *nonfinite);
int ss_solver_newton_create(ss_sim *sim, char *err, int err_sz);
int ss_solver_qn_create(ss_sim *sim, char *err, int err_sz);
/* Energy and gradient g at the unknowns xd (scattered into xfull_t), timed
 * into st's assemble_ms. */
double ss_sim_energy_at(ss_sim *sim, ss_sim_stats *st, const double *xd, double *g);
/* A line search's first trial step along dir from xd (slope E's slope there,
 * < 0), asked of the energy terms: the shortest any term's own model of the
 * line gives, 1 where none has one (sim_energy.c). */
double ss_sim_energy_first_trial(ss_sim *sim, const double *xd, const double *dir, double slope);

#endif
