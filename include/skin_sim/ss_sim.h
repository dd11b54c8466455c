/* skin_sim core: the dynamic skin (doc/model.md, "The skin model").
 *
 * One ss_sim simulates a triangle-mesh skin sliding over a moving body mesh:
 * implicit Euler posed as the minimisation of
 *   E(x) = 1/(2 h^2) |x - x_pred|_M^2 + membrane + anchor springs (+ bending)
 * solved by Newton or by quasi-Newton (L-BFGS), followed by the anchor update
 * (the spring force drags each anchor over the body by walk, project or nring).
 *
 * Model and data: topology, rest shape and settings are fixed at create, where
 * all memory is allocated. With the quasi-Newton solver ss_sim_step allocates
 * nothing at a constant dt (a new dt refactors a matrix, and CHOLMOD allocates
 * temporaries inside cholmod_factorize, as it does in every Newton iteration).
 * Deterministic: the same inputs give the same bits. The quasi-Newton path
 * uses no BLAS; Newton's supernodal factorisation goes through the BLAS,
 * whose results are reproducible for a given BLAS and thread count (e.g.
 * OPENBLAS_NUM_THREADS) but may differ across them.
 *
 * Units are SI by convention (metres, seconds, kilograms), but any consistent
 * set works: only ratios matter. Do not reach into the struct behind ss_sim. */
#ifndef SKIN_SIM_SS_SIM_H
#define SKIN_SIM_SS_SIM_H

#include "ss_anchor.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A skin face of rest area below SS_SLIVER_AREA times the mean rest edge
 * length squared is a sliver: its normal swings with the smallest move of a
 * corner, so it is judged neither by the orient term (it does not resist
 * turning over) nor by the inverted-face count of runs (ss_run_stats). */
#define SS_SLIVER_AREA 0.01

/* ---- settings ------------------------------------------------------------- */

enum ss_solver {
  SS_SOLVER_NEWTON = 0,       /* projected Newton, CHOLMOD factorisation per iteration */
  SS_SOLVER_QUASI_NEWTON = 1  /* L-BFGS on a constant Hessian factored once per time step */
};
/* "newton", "quasi-newton"; NULL for an unknown value. */
const char *ss_solver_name(int solver);
/* Parses a solver name; returns the ss_solver or -1 if unknown. */
int ss_solver_parse(const char *name);

/* Definition of a simulation; get one from ss_sim_default_settings() and
 * change what you need. Every field but face_mask has its default, range and
 * unit in ONE place, the settings table (ss_settings.h, src/core/settings.c;
 * `skinsim settings` lists it), which ss_sim_default_settings() and the checks
 * read: the comments below say what a field means, not its value. Stiffnesses
 * are per unit REST AREA of skin, so a refined mesh behaves the same. */
typedef struct ss_sim_settings {
  int solver;            /* ss_solver */
  double dt;             /* s; frame time step used when ss_sim_step gets dt <= 0 */
  int substeps;          /* implicit Euler steps per ss_sim_step (body pose interpolated
                            linearly in between): at one substep the error is the step's
                            (Newton converged there is as far from the truth as
                            quasi-Newton), so the default budget goes into substeps */
  int iterations;        /* max solver iterations per substep: the real-time budget of
                            quasi-Newton (the defaults fit 30 Hz at 19k triangles on one
                            core: doc/benchmarks.md); raise it (e.g. 50-500) for Newton or
                            tight tolerances */
  double tol;            /* convergence: max over vertices of |gradient| / (mass/h^2 * mean
                            rest edge length), i.e. roughly the position error in edge
                            lengths */
  double safety_residual; /* quasi-Newton: a substep whose residual (same measure as tol) is
                            still above this after `iterations`, or that ends with a face
                            squeezed below a tenth of its rest area, keeps iterating, up to
                            iterations_max: a hard frame costs more instead of tangling the
                            skin; 0 turns it off */
  int iterations_max;    /* the hard cap for that */
  int lbfgs_history;     /* L-BFGS pairs kept (quasi-Newton) */
  double young;          /* N/m: membrane Young's modulus times thickness */
  double poisson;        /* Poisson ratio */
  double density;        /* kg/m^2: mass per rest area */
  double anchor_stiffness; /* N/m per m^2 of skin: zero-length anchor springs (with the
                              default density the default rings at sqrt(k/rho) ~ 32 rad/s,
                              5 Hz, a soft adipose layer, and lags a/k s^2 behind a body
                              accelerating at a) */
  int barycenter_anchors;  /* 1: a spring at every face barycenter too (the springs of
                              vertices and barycenters then share the stiffness half and
                              half) */
  double bending;        /* hinge bending stiffness k (N m); 0 = off */
  double gravity[3];     /* m/s^2 */
  double damping;        /* 1/s: mass-proportional damping */
  double slide;          /* 1/s, >= 0: how fast an anchor follows the skin point it holds. In a
                            substep of h seconds it goes a fraction 1 - exp(-slide h) of the
                            way (a* = a0 + that (p - a0), then carried there by the mover): a
                            relaxation with time constant 1/slide s, the same physics at any
                            substep count. 0 glues the skin to the body, +inf (INFINITY)
                            is frictionless (the whole way every substep). 30 ln 2 = 20.79 /s
                            is half the way per 1/30 s frame */
  double tether;         /* 1/s, >= 0: the connective tissue under the skin. After its slide, each
                            anchor WALKS back along the body surface (the walk, whatever the
                            method, so it cannot jump across a gap) towards the point where it
                            was bound, a fraction 1 - exp(-tether h) of the straight way there
                            in a substep of h seconds: a relaxation rate independent of the step
                            (a time constant of 1/tether s). Except near home: with the walk,
                            an anchor in its home face slides within it (to the face's point nearest its
                            slide's target) unless the target lies beyond the face's
                            neighbours (outside the face grown to four times its size about
                            its centroid), and one whose slide ends in a face sharing a corner
                            with its home face is put on the home face's point nearest that
                            step's end, so it stays on its home face unless one substep's
                            slide carries it past the faces around it (under a steady pull
                            along a flat body the vertex anchors stay at home and the others
                            on their home face whatever the tether, 0.3 or 3 /s: a leash more
                            than a rate; doc/model.md, "Anchor update"). 0 = the paper's
                            free sliding */
  double orient;         /* N/m (energy per m^2 of rest skin, as young), >= 0: the skin lies face up
                            on its body. Each skin face whose area projected on the tangent plane
                            of the body under it (signed, over its rest area: 1 flat, 0 on edge,
                            -1 turned over) falls below 0.2 pays orient (0.2 - s)^2 / 2 per m^2;
                            without it a face can turn over at full area at no cost and a
                            crease folded flat locks (orient.c). 0 = off */
  double compression;    /* in (0, 1]: the membrane's stiffness where it is compressed, as a
                            share of its stiffness in tension (principal stretches and area
                            below rest; membrane.c). Skin wrinkles far below an edge's scale;
                            a mesh as stiff in compression as in tension buckles in folds one
                            edge wide that turn over where the body under them is crushed.
                            1 = the Stable Neo-Hookean membrane */
  int collide;           /* 1: after the last substep's solve, free skin vertices behind the
                            body's surface around their anchor are moved out of it (collide.c;
                            not where the body passes through itself) */
  double collide_thickness; /* mean rest edge lengths kept between skin and body by collide,
                            in [0, 1] */
  ss_mover_settings mover; /* how anchors move (walk/project/nring), ss_mover_default_settings() */
  int threads;           /* threads for per-face energies and anchor walks (OpenMP); 0: all
                            cores for a skin of 4000 faces or more, else 1, and only while
                            they pay (every 50 steps 3 run on all, 3 on one, the rest on the
                            faster).
                            The results are the same bits for any count; 2 pays on an idle
                            2-core machine, and costs where the cores are busy (e.g. tests
                            running in parallel: ask for 1 there) */
  const unsigned char *face_mask; /* (skin nface) non-zero: simulate this face; NULL = all.
                                     Copied at create. Vertices of no simulated face follow
                                     the body; vertices on the region's border are pinned. */
} ss_sim_settings;

ss_sim_settings ss_sim_default_settings(void);

/* ---- life cycle ------------------------------------------------------------ */

/* A separate skin mesh (flat arrays owned by the caller, read at create only). */
typedef struct ss_sim_mesh {
  int nvert;
  const double *pos;  /* (nvert x 3) rest positions, placed on the body at rest */
  int nface;
  const int *faces;   /* (nface x 3) */
} ss_sim_mesh;

/* Where ss_sim_create binds a separate skin, before creating it: each skin
 * vertex's closest point on the body at rest. dist (skin nvert, may be NULL)
 * gets its distance (metres); with body_part (body nvert, as for
 * ss_mesh_rigid_pieces; may be NULL), skin_part (skin nvert, may be NULL)
 * gets the part the body face under it moves with (its three corners' part
 * where they agree, else 0), so that ss_mesh_rigid_pieces on the skin finds
 * the skin's pieces that ride one rigid link. Returns SS_OK, or SS_E_MESH /
 * SS_E_NONFINITE / SS_E_NOMEM with a message in err. */
int ss_sim_skin_binding(int body_nvert, const double *body_rest, int body_nface,
                        const int *body_faces, const ss_sim_mesh *skin, const uint32_t *body_part,
                        uint32_t *skin_part, double *dist, char *err, int err_sz);

typedef struct ss_sim ss_sim;
/* The fixed part of a sim (topology, rest data, masses, sparsity): see ss_model_create. */
typedef struct ss_model ss_model;

/* Creates a simulation on a body mesh at rest (body_rest: nvert x 3, faces:
 * nface x 3, both read at create only). skin: NULL makes the skin a copy of
 * the body at rest, its anchors at its own vertices; else each skin vertex and
 * barycenter is bound once to the closest point of the body at rest. Returns
 * SS_OK, or an error (SS_E_ARG bad settings, SS_E_MESH, SS_E_NONFINITE,
 * SS_E_NOMEM, SS_E_SOLVER) with a message in err; *out is NULL on error. */
int ss_sim_create(ss_sim **out, int body_nvert, const double *body_rest, int body_nface,
                  const int *body_faces, const ss_sim_mesh *skin,
                  const ss_sim_settings *settings, char *err, int err_sz);
void ss_sim_destroy(ss_sim *sim);

/* ---- one model, several sims --------------------------------------------------
 * A sim is a MODEL (topology, rest data, masses and springs, hinges, the
 * sparsity pattern: everything fixed once built, never written while
 * stepping) and the DATA of its run (state, anchors, solver workspaces).
 * Several sims may run on one model: a reference or truth run of a skin, a
 * second skin of the same body. They share its material, the settings whose
 * scope is SS_SCOPE_MODEL in the settings table (ss_settings.h), and
 * face_mask; each has its own run settings (scope SS_SCOPE_RUN), and the
 * same bits as a sim made by ss_sim_create with the same settings.
 * A model is a value: built once, never written afterwards (a live change of
 * a model setting, ss_sim_set_settings, moves that sim onto a new model).
 * Reference counted (atomically): a model lives while its creator's
 * reference (ss_model_destroy) or any sim on it (ss_sim_destroy) does, so
 * the two may be dropped in any order, on any thread. */

/* Builds a model as ss_sim_create would (same arguments, same errors), with no
 * sim on it; release it with ss_model_destroy. */
int ss_model_create(ss_model **out, int body_nvert, const double *body_rest, int body_nface,
                    const int *body_faces, const ss_sim_mesh *skin,
                    const ss_sim_settings *settings, char *err, int err_sz);
/* Drops the creator's reference (NULL: nothing). */
void ss_model_destroy(ss_model *model);
/* A sim on model (it takes a reference), at rest. settings: NULL for those the
 * model was built with; else its model settings (above) must be the model's,
 * else SS_E_ARG naming the first that differs. Other errors as ss_sim_create. */
int ss_sim_create_from_model(ss_sim **out, const ss_model *model, const ss_sim_settings *settings,
                             char *err, int err_sz);
/* The model sim runs on (valid while sim is; pass it to ss_sim_create_from_model
 * to run another sim on it). */
const ss_model *ss_sim_model(const ss_sim *sim);
/* The body a model was built on: its vertex and face counts. */
int ss_model_body_nvert(const ss_model *model);
int ss_model_body_nface(const ss_model *model);

/* Back to the rest state (skin at rest, zero velocity, anchors as bound at
 * create), e.g. when time goes backwards. */
void ss_sim_reset(ss_sim *sim);

/* Sets the skin's positions (nvert x 3) and velocities (NULL: zero), e.g.
 * to start from a deformed state. SS_E_NONFINITE if any value is not finite
 * (the state is then untouched). */
int ss_sim_set_state(ss_sim *sim, const double *pos, const double *vel, char *err, int err_sz);

/* Changes the settings of a simulation from its next step on, keeping its state
 * and anchors (live tuning). Checks them first: SS_E_ARG naming the bad setting,
 * nothing changed. How each setting reaches the sim is its `apply` in the
 * settings table (ss_settings.h): from the next step, or with its matrices
 * refactored on the next substep (SS_APPLY_REFACTOR). A setting that changes
 * the skin's structure (SS_APPLY_RECREATE; bending turned on or off) cannot
 * change in place: then nothing changes, *recreate (may be NULL) is set to 1,
 * err names the setting and SS_OK is returned: create the simulation again with
 * the settings. settings->face_mask is ignored (the simulated region stays).
 * A change of a model setting (scope SS_SCOPE_MODEL) moves this sim onto a new
 * model with that material, which shares the old one's structure; other sims
 * on the old model keep it, unwritten (this allocates the new model's arrays;
 * run settings alone allocate nothing). */
int ss_sim_set_settings(ss_sim *sim, const ss_sim_settings *settings, int *recreate, char *err,
                        int err_sz);

/* ---- stepping -------------------------------------------------------------- */

/* What one ss_sim_step did (sums over its substeps unless said otherwise). */
typedef struct ss_sim_stats {
  double total_ms;     /* the whole step */
  double pose_ms;      /* the body's per-face frames (and BVH refit) of each substep pose,
                          anchor positions, fixed vertices put on their anchors */
  double walk_ms;      /* anchor updates (ss_mover_move: walk, project or nring) */
  double assemble_ms;  /* energies, gradients and (Newton) Hessian assembly */
  double factor_ms;    /* CHOLMOD numeric factorisations */
  double solve_ms;     /* CHOLMOD triangular solves and the L-BFGS two-loop */
  double linesearch_ms; /* the line searches' own work (vector passes, the first trial's
                           model), their energy evaluations not included (assemble_ms) */
  double orient_ms;    /* each substep's energy set-up: inertia targets, the orient term's
                          body normals under the skin, the skin's normals at the start */
  int substeps;
  int iterations;      /* solver iterations, all substeps */
  int factorizations;
  int energy_evaluations; /* energy-and-gradient evaluations by the solver, all substeps */
  double residual;     /* final convergence measure of the last substep (see tol): the
                          worst vertex */
  double residual_rms; /* the same measure, root mean square over the free vertices */
  double energy;       /* final incremental energy E(x) of the last substep */
  int converged;       /* 1 if every substep reached tol */
  int stalled;         /* substeps that stopped because no step decreased the energy */
  int failures;        /* substeps that met a non-finite value (the last good state kept) */
  int anchors_moved;   /* anchor updates done */
  int anchors_boundary;   /* ... that stopped on a boundary edge (walk) */
  int anchors_crease;     /* ... that stopped at a crease (walk) */
  int anchors_step_limit; /* ... that hit walk_max_steps */
  int walk_steps;      /* edges crossed by all walks */
  double min_area_ratio; /* over simulated faces after the step: area / rest area */
  double max_area_ratio;
  int threads;         /* threads the step ran on (with threads 0, as the probe chose) */
} ss_sim_stats;

/* Advances by dt (<= 0: settings dt) to the body pose body_pos (body nvert x
 * 3). stats may be NULL. Returns SS_OK (even if a substep stalled or failed:
 * see stats), or SS_E_ARG / SS_E_NONFINITE for bad input (message in err; the
 * state is untouched), or SS_E_SOLVER if CHOLMOD failed (the last good state
 * kept). Never leaves NaN or Inf in the state. */
int ss_sim_step(ss_sim *sim, const double *body_pos, double dt, ss_sim_stats *stats,
                char *err, int err_sz);

/* ---- warnings -------------------------------------------------------------- */

/* What went wrong while stepping, counted over the life of a sim (as MuJoCo's
 * mjData.warning): a step's ss_sim_stats say what happened in it, these keep
 * the total for a caller that looks once a minute (a node's diagnostics).
 * ss_sim_reset does not clear them (a node that resets its skin on a time
 * jump still reports the hour's failures); ss_sim_clear_warnings does. */
typedef enum ss_warning_kind {
  SS_WARN_REFUSED = 0,  /* a step refused before anything changed: a non-finite body pose or a
                           move whose velocity overflows (SS_E_NONFINITE); info: the vertex */
  SS_WARN_FAILURE,      /* a substep met a non-finite value, the last good state kept
                           (stats.failures); info: failures in that step */
  SS_WARN_SOLVER,       /* CHOLMOD failed (SS_E_SOLVER); info: its status */
  SS_WARN_STALLED,      /* a substep stopped where no step lowered the energy; info: substeps */
  SS_WARN_UNCONVERGED,  /* a step ended with a substep above tol; info: substeps in the step */
  SS_WARN_STEP_LIMIT,   /* anchor updates that hit walk_max_steps; info: how many in the step */
  SS_NWARNING
} ss_warning_kind;

typedef struct ss_warning {
  long long number;     /* steps in which it happened */
  long long last_step;  /* the step it last happened in (1 = the first step after create;
                           a refused step has the number the step would have had); 0: never */
  int last_info;        /* what it was then (see ss_warning_kind) */
} ss_warning;

/* SS_NWARNING entries, indexed by ss_warning_kind (valid while sim is). */
const ss_warning *ss_sim_warnings(const ss_sim *sim);
/* Steps taken since create (refused steps not counted). */
long long ss_sim_step_count(const ss_sim *sim);
void ss_sim_clear_warnings(ss_sim *sim);
/* Short name of a warning kind ("refused", "failure", ...; "unknown" out of range). */
const char *ss_warning_name(int kind);

/* ---- reading back ---------------------------------------------------------- */

const ss_sim_settings *ss_sim_get_settings(const ss_sim *sim); /* face_mask points inside sim */
int ss_sim_skin_nvert(const ss_sim *sim);
int ss_sim_skin_nface(const ss_sim *sim);
const int *ss_sim_skin_faces(const ss_sim *sim);        /* (nface x 3) */
const double *ss_sim_skin_rest(const ss_sim *sim);      /* (nvert x 3) */
const double *ss_sim_skin_positions(const ss_sim *sim); /* (nvert x 3), current */
const double *ss_sim_skin_velocities(const ss_sim *sim);/* (nvert x 3), current */
/* Number of free vertices (the unknowns), after the face mask. */
int ss_sim_ndof(const ss_sim *sim);

/* Anchors: first one per skin vertex (index v), then, with barycenter anchors
 * on, one per skin face (index nvert + f). Each lives on the BODY as
 * (face, u, v). */
int ss_sim_nanchors(const ss_sim *sim);
const int *ss_sim_anchor_faces(const ss_sim *sim);  /* (nanchors) body face */
const double *ss_sim_anchor_uv(const ss_sim *sim);  /* (nanchors x 2) */
/* What the last ss_sim_step did to each anchor, summed over its substeps:
 * pull, the distance |a* - a0| from the anchor to the candidate it was sent
 * towards; path, the length walked on the body surface (0 unless the method
 * is walk). (nanchors) each; zero for anchors that did not move. They let a
 * caller tell an honest slide from a jump across a gap (a snag). Measured
 * only after ss_sim_measure_anchors(sim, 1) (NULL until then, and after
 * turning it off): they cost square roots on every anchor's walk, each
 * substep (a sixth of the anchor stage on the 19k quadruped), and change
 * nothing of the simulation. */
const double *ss_sim_anchor_pull(const ss_sim *sim);
const double *ss_sim_anchor_path(const ss_sim *sim);
void ss_sim_measure_anchors(ss_sim *sim, int on);
/* World positions of the anchors in the current body pose into out
 * (nanchors x 3). */
void ss_sim_anchor_positions(const ss_sim *sim, double *out);
/* Sizes of the body given at create: body_pos of ss_sim_step holds
 * ss_sim_body_nvert x 3 values (callers receiving meshes check this). */
int ss_sim_body_nvert(const ss_sim *sim);
int ss_sim_body_nface(const ss_sim *sim);
/* What a user sees go wrong, counted plainly in the current state: skin
 * faces turned more than 90 degrees against the body under them (the body
 * face holding the face's barycenter anchor, else its corners' anchors),
 * against how they lay at rest, slivers and faces over sharp turns included;
 * and skin vertices farther than one mean rest edge length from the body
 * near their anchor (its face and the faces across its edges: their distance
 * to the body where the body closest to them is there, else a bound from
 * above). Either pointer may be NULL. O(faces + vertices), allocates nothing. */
void ss_sim_count_off_body(const ss_sim *sim, int *faces_turned, int *vertices_far);
/* Body topology, as built at create (for metrics that need it). */
const ss_topo *ss_sim_body_topo(const ss_sim *sim);

#ifdef __cplusplus
}
#endif
#endif
