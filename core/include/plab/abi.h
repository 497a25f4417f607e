/* ParticleLab plug-in ABI — the only contract between the host (plab) and a
 * plug-in library. Plain C so that a plug-in built by another compiler, or
 * years later, still loads: no exceptions, no std:: or Eigen types, no memory
 * freed on the other side of the boundary.
 *
 * A library exports two symbols:
 *   uint32_t plab_plugin_abi_version(void);        -- PLAB_ABI_VERSION it was built with
 *   int      plab_plugin_init(const plab_registrar*);  -- registers its models/passes/materials
 * The host checks the version before calling init: it loads a plug-in of its
 * own major version (PLAB_ABI_MAJOR) and a minor version no newer than its
 * own, and refuses any other by name (a plug-in of ABI 1 returns 1 to 7).
 *
 * Every struct that crosses the boundary begins with its size in bytes
 * (`size`), set by whoever fills it (the C++ adapters do it for a plug-in):
 * a later minor version may append members, and the reader of a struct
 * refuses one smaller than it needs. An array of descriptions is read with
 * the stride of its first element's size.
 *
 * What each version changed: docs/abi-changes.md.
 *
 * Contact models are called once per *batch* of contacts over host-owned
 * structure-of-arrays data (plab_contact_batch). The host packs every
 * batch with the rows in contact only (ball–ball and ball–wall, either
 * stage) and the inputs the model declares (`io`), and itself resets the
 * history of a contact out of the activity range to the declared defaults.
 * A model must not rely on seeing an inactive row (a test harness may still
 * pass one: the C++ adapter forgets its history). Passes are called once
 * per cycle phase over all bodies (plab_pass_view).
 *
 * Most authors never touch this file: contact_model.hpp and pass.hpp generate
 * the tables and the batch loop from a C++ class.
 */
#ifndef PLAB_ABI_H
#define PLAB_ABI_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PLAB_ABI_MAJOR 2u
#define PLAB_ABI_MINOR 4u
/* what plab_plugin_abi_version() returns: major << 16 | minor (ABI 1
 * returned its plain version number, 1 to 7, whose major reads as 0) */
#define PLAB_ABI_VERSION ((PLAB_ABI_MAJOR << 16) | PLAB_ABI_MINOR)

/* ---- descriptions ------------------------------------------------------ */

/* What a property's value is. The value handed to the plug-in is always a
 * double (in `props`, in declaration order); the kind says how the scene
 * writes it and how the host checks it. */
#define PLAB_KIND_NUMBER 0u  /* a real number in [min_value, max_value] */
#define PLAB_KIND_INTEGER 1u /* a whole number in [min_value, max_value] (a count) */
#define PLAB_KIND_BOOL 2u    /* true / false in the scene; 1 / 0 to the plug-in */
#define PLAB_KIND_CHOICE 3u  /* one of `choices` by name in the scene; its index to the plug-in */
#define PLAB_KIND_GROUP 4u   /* a group by name in the scene; its index to the plug-in
                              * (groups are numbered in the order the scene first names them) */

/* Flags of a property. The bounds of a number or integer are inclusive
 * unless flagged. */
#define PLAB_MIN_EXCLUSIVE 1u
#define PLAB_MAX_EXCLUSIVE 2u
#define PLAB_GROUP_NONE_ALLOWED 8u /* kind GROUP: the scene may say null or "none",
                                    * handed as -1 (then the default); without it
                                    * the scene must name a group */

/* How the host combines the values two materials give a property when a
 * contact rule joins groups of different materials (scene.materials):
 * harmonic 2ab/(a+b), arithmetic (a+b)/2, geometric sqrt(ab), max, min.
 * PLAB_MIX_NONE: the two must agree (the host refuses the rule otherwise).
 * Only numbers mix; an integer may take max or min. */
#define PLAB_MIX_NONE 0u
#define PLAB_MIX_HARMONIC 1u
#define PLAB_MIX_ARITHMETIC 2u
#define PLAB_MIX_GEOMETRIC 3u
#define PLAB_MIX_MAX 4u
#define PLAB_MIX_MIN 5u

typedef struct plab_property_desc {
    uint32_t size;        /* sizeof(plab_property_desc) */
    uint32_t kind;        /* PLAB_KIND_* */
    const char* key;      /* scene key, e.g. "kn" */
    const char* name;     /* field vocabulary, e.g. "normal stiffness" */
    const char* unit;     /* SI unit, e.g. "N/m"; "1" for dimensionless (and for
                           * bools, choices and groups) */
    double default_value; /* used when the scene does not set it: a number, 0/1
                           * for a bool, an index into `choices`, -1 for a group
                           * (none, or: the scene must name one) */
    double min_value;     /* number, integer: valid range [min, max] (see flags); */
    double max_value;     /* the host ignores them for the other kinds */
    uint32_t flags;       /* PLAB_MIN_EXCLUSIVE, PLAB_MAX_EXCLUSIVE, PLAB_GROUP_NONE_ALLOWED */
    uint32_t mixing;      /* PLAB_MIX_* */
    const char* const* choices; /* kind CHOICE: choice_count names (e.g. "cubic"), */
    uint32_t choice_count;      /* value i is choices[i]; NULL / 0 otherwise */
    const char* doc;
} plab_property_desc;

/* A material (ABI 2.1): a named set of properties that the models and
 * passes of a package share, e.g. the SPH package's "sph_fluid" (rest
 * density, speed of sound, smoothing length, kernel, ...). A scene states
 * their values once per group (scene.materials); a model or pass that names
 * the material (its description's `material`) takes from the scene
 * materials of its groups the values of those of its own properties that
 * the material declares, and no others. Such a property is declared in the
 * model's or pass's `properties` as the material declares it (the same key,
 * kind, unit, default, range, flags, mixing rule and choices; name and doc
 * may differ), which the host checks; a model or pass that names a material
 * declares at least one of its properties. Several libraries may register
 * one material, each time with the same properties in the same order (a
 * package's SDK header declares them once); the host refuses another. A
 * material is registered before the models and passes that name it, by
 * their library or by one loaded before. */
typedef struct plab_material_desc {
    uint32_t size;     /* sizeof(plab_material_desc) */
    const char* name;  /* e.g. "sph_fluid"; materials have names of their own (not models' or passes') */
    const char* doc;
    uint32_t property_count;
    const plab_property_desc* properties;
} plab_material_desc;

/* What a history slot does when the two ends of a contact are swapped. */
#define PLAB_SWAP_KEEP 0u   /* scalar (e.g. bond state) */
#define PLAB_SWAP_NEGATE 1u /* component of a vector acting on end 2 */

/* Flags of a history slot. PLAB_HISTORY_TANGENTIAL: the slot and the two
 * after it are the x, y, z of a vector that lies in the contact plane (a
 * shear force). Before each call of compute() the host turns it, in every
 * active row, into the row's current plane: the component along `normal`
 * projected out and the magnitude restored (PFC's rotation of the shear
 * force with the contact plane); a zero vector stays zero, and one with
 * nothing left in the plane becomes zero. The law then reads it as already
 * in the plane. */
#define PLAB_HISTORY_TANGENTIAL 1u
#define PLAB_HISTORY_KNOWN_FLAGS PLAB_HISTORY_TANGENTIAL

typedef struct plab_history_desc {
    uint32_t size; /* sizeof(plab_history_desc) */
    const char* name;
    double default_value;
    uint32_t swap_rule;
    const char* doc;
    uint32_t flags; /* PLAB_HISTORY_*, on the first slot of a vector; a
                     * description whose `size` ends before it reads as 0 */
} plab_history_desc;

/* How the activity range of a model is measured. */
#define PLAB_RANGE_GAP 0u      /* active while surface gap <= value  */
#define PLAB_RANGE_DISTANCE 1u /* active while centre distance <= value */

/* A per-body field a model or pass reads, or accumulates into. */
typedef struct plab_field_desc {
    uint32_t size;    /* sizeof(plab_field_desc) */
    const char* name; /* e.g. "sph_density" */
    const char* unit;
    double default_value;
} plab_field_desc;

/* ---- the contact batch --------------------------------------------------- */

/* Host-owned columns for `count` contacts. Vectors are packed xyz triples
 * (3*count doubles); in 2D the z components are zero. No two columns
 * overlap, so a model may work on several rows at once (only the accumulate
 * columns of a batch whose sums are not kept may share one scratch column,
 * see above). Convention: the normal points from end 1 to end 2 and `force`
 * is the force acting ON END 2 (end 1 receives -force), as in PFC. */
typedef struct plab_contact_batch {
    uint32_t size;       /* sizeof(plab_contact_batch), set by the host */
    uint32_t dim;        /* 2 or 3 */
    uint32_t count;      /* contacts in this batch */
    uint32_t end2_is_wall; /* 1: end 2 is a wall facet (infinite mass) */
    uint32_t history_stride; /* doubles per history row */
    double dt;           /* timestep, s; 0: re-evaluate forces at this state without advancing history */

    /* inputs, one entry per contact */
    const int32_t* end1;            /* body index of end 1 */
    const int32_t* end2;            /* body index, or facet index if wall */
    const uint8_t* active;          /* 0: outside the activity range; such a row
                                     * has gap and distance set, its other
                                     * inputs are unspecified (not computed) */
    const double* normal;           /* 3*count, unit */
    const double* gap;              /* surface gap, m (negative: overlap) */
    const double* distance;         /* centre(-to-surface) distance, m */
    const double* rel_velocity;     /* 3*count, v(end2) - v(end1) at the contact point, m/s */
    const double* rel_angular_velocity; /* 3*count, w2 - w1, rad/s */
    const double* radius1;          /* m */
    const double* radius2;          /* m (0 for walls) */
    const double* mass1;            /* kg */
    const double* mass2;            /* kg (+inf for walls) */
    const double* eff_mass;         /* m1 m2/(m1+m2), kg */
    const double* eff_radius;       /* r1 r2/(r1+r2), m */

    /* per-body field columns the model declared in `fields_read`, in that
     * order, indexed by body index (end1[k] / end2[k]); when end2_is_wall,
     * end2[k] is a facet index and must not index a body column */
    const double* const* body_fields;

    /* in/out: history rows, history_stride doubles per contact; the
     * tangential vectors (PLAB_HISTORY_TANGENTIAL) of the active rows
     * already turned into their current contact plane */
    double* history;

    /* outputs, one entry per contact, zeroed by the host first (dt_limit:
     * +inf); an inactive row's (a harness's) are ignored */
    double* force;        /* 3*count, on end 2, N */
    double* moment1;      /* 3*count, pure moment on end 1 (beyond r x F), N m */
    double* moment2;      /* 3*count, pure moment on end 2, N m */
    double* strain_energy;   /* stored elastic energy, J (a state, not an increment) */
    double* slip_energy;     /* energy dissipated by friction this step, J */
    double* dashpot_energy;  /* energy dissipated by dashpots this step, J */
    /* stable timestep, PFC style: per body dt = sqrt(m / sum k_t) and
     * sqrt(I / sum k_r) over its contacts. The host adds the arm term
     * k_t |r_c|^2 to k_r itself, so a model reports only pure rotational
     * stiffness (e.g. a bond's bending stiffness). */
    double* stiffness_translational; /* N/m */
    double* stiffness_rotational;    /* N m/rad */
    double* dt_limit;        /* s: a direct step limit (e.g. SPH CFL), +inf if none */
    /* accumulations into fields declared in `fields_accumulated`:
     * accumulate1[f][k] adds to body end1[k], accumulate2[f][k] to end2[k] */
    double* const* accumulate1;
    double* const* accumulate2;
    double* break_energy;    /* elastic energy a bond released by breaking this step, J */
    uint32_t stage;          /* PLAB_STAGE_FORCES, or PLAB_STAGE_RATES for a model with rates_stage */
    /* bit f (f < 64) set: body_fields[f] holds the default
     * the model declared for it at every body, in this call (the host
     * checked: nothing in the scene writes the field, and its values are
     * the default). A model may then take the default instead of reading
     * the column; 0 claims nothing. */
    uint64_t body_fields_at_default;
} plab_contact_batch;

/* Stages of the force-displacement phase. A model with `rates_stage` is
 * called twice per cycle over the same geometry: first to accumulate field
 * rates (e.g. the SPH continuity sum), then — after the passes of phase
 * PLAB_PHASE_RATES_DONE have turned rates into states (density, pressure) —
 * to compute forces. Other models see only PLAB_STAGE_FORCES. */
#define PLAB_STAGE_FORCES 0u
#define PLAB_STAGE_RATES 1u

typedef struct plab_contact_model_desc {
    uint32_t size;    /* sizeof(plab_contact_model_desc) */
    const char* name; /* as named in scenes, e.g. "linear" */
    const char* doc;
    uint32_t property_count;
    const plab_property_desc* properties;
    uint32_t history_count;
    const plab_history_desc* history;
    uint32_t range_kind;                     /* PLAB_RANGE_GAP / DISTANCE */
    const char* timestep_rule;               /* human text for `plab plugins --describe` */
    /* activity range from the instance's property values (same order as
     * `properties`); must be finite */
    double (*activity_range)(const double* props);
    uint32_t fields_read_count;
    const plab_field_desc* fields_read;
    uint32_t fields_accumulated_count;
    const plab_field_desc* fields_accumulated;
    /* instance life cycle; create may return NULL when no state is needed */
    void* (*create)(const double* props);
    void (*destroy)(void* instance);
    /* force-displacement over one batch; returns 0 on success */
    int (*compute)(void* instance, const double* props, const plab_contact_batch* batch);
    /* Bonds: index of a history slot that keeps a contact alive, or -1.
     *   > 0  bonded: active at any gap, carried across neighbour rebuilds
     *   < 0  just broken, mode = -value (PLAB_BREAK_*): the host records
     *        where and when, then sets the slot to 0
     *   = 0  unbonded: ordinary activity range
     * The host's `bond` command sets it to 1 on chosen contacts. */
    int32_t persist_slot;
    /* 1: call compute() in the rates stage too (see PLAB_STAGE_RATES); its
     * accumulations are summed after that stage, not after the force stage */
    uint32_t rates_stage;
    /* PLAB_MODEL_* bits */
    uint32_t flags;
    /* PLAB_IO_* bits, PLAB_IO_DECLARED among them (mandatory, see below) */
    uint32_t io;
    /* ABI 2.1: the name of the material (plab_material_desc) whose
     * properties this model takes from a scene's materials, or NULL: it takes
     * none. A description of ABI 2.0 (a `size` that ends before this member)
     * is read as NULL. */
    const char* material;
} plab_contact_model_desc;

/* `io`: what a model reads and writes beyond what every model
 * gets (end1, end2, active, normal, gap, distance, rel_velocity, history,
 * dt, body fields) and must write (force; strain, slip and dashpot energy and
 * stiffness_translational, zeroed by the host). The declaration is
 * mandatory: the host refuses a model whose `io` lacks PLAB_IO_DECLARED
 * (PLAB_IO_DECLARED alone declares nothing optional). An input not named
 * is not computed (it may hold NaN), an output not named is neither zeroed
 * nor read (pure moments and rotational stiffness count as zero, dt_limit
 * as no limit, break energy as zero). Before the first step the host calls
 * the model once on a touching contact whose undeclared inputs are NaN and
 * undeclared outputs are NaN sentinels, and refuses it, naming the column,
 * if the force turns NaN or a sentinel is overwritten. */
#define PLAB_IO_DECLARED (1u << 31)
#define PLAB_IO_REL_ANGULAR_VELOCITY 2u  /* input: rel_angular_velocity */
#define PLAB_IO_RADII 4u                 /* inputs: radius1, radius2 */
#define PLAB_IO_MASSES 8u                /* inputs: mass1, mass2 */
#define PLAB_IO_EFF_MASS 16u             /* input: eff_mass */
#define PLAB_IO_EFF_RADIUS 32u           /* input: eff_radius */
#define PLAB_IO_MOMENTS 256u             /* outputs: moment1, moment2 */
#define PLAB_IO_STIFFNESS_ROTATIONAL 512u /* output: stiffness_rotational */
#define PLAB_IO_DT_LIMIT 1024u           /* output: dt_limit */
#define PLAB_IO_BREAK_ENERGY 2048u       /* output: break_energy */
#define PLAB_IO_KNOWN_BITS (PLAB_IO_DECLARED | 62u | 256u | 512u | 1024u | 2048u)

/* PLAB_MODEL_FORCE_AT_CENTRES: the pair force acts between the
 * two particle centres, as in SPH (an interaction of points, not a touching
 * surface). For its ball-ball contacts the host passes the relative velocity
 * of the centres and zero rel_angular_velocity, applies no moment (neither
 * r x F nor moment1/moment2), and reads no stiffness (stiffness_*) or energy
 * (strain/slip/dashpot/break) outputs: the model's step limit is its
 * dt_limit. Balls with such contacts should have their rotation fixed. */
#define PLAB_MODEL_FORCE_AT_CENTRES 1u
#define PLAB_MODEL_KNOWN_FLAGS PLAB_MODEL_FORCE_AT_CENTRES

#define PLAB_BREAK_TENSION 1
#define PLAB_BREAK_SHEAR 2

/* ---- passes over bodies --------------------------------------------------- */

#define PLAB_PHASE_PRE_FORCE 0u  /* after detection, before force-displacement */
#define PLAB_PHASE_POST_FORCE 1u /* after forces are summed onto bodies */
#define PLAB_PHASE_INTEGRATE 2u  /* after the law of motion, integrate own fields */
#define PLAB_PHASE_RATES_DONE 3u /* after the rates stage, before forces: rates → states */
/* after the first half kick (velocities at t + dt/2, positions
 * and contacts of the last force pass), before the drift; a pass of this
 * phase may fill the fields named below, which the drift adds to the
 * velocity it moves a body with (e.g. XSPH, thesis eq. 18). The velocity
 * itself is not changed: momentum and kinetic energy stay the leapfrog's. */
#define PLAB_PHASE_PRE_DRIFT 4u
#define PLAB_DRIFT_CORRECTION_X "drift_velocity_correction_x"
#define PLAB_DRIFT_CORRECTION_Y "drift_velocity_correction_y"
#define PLAB_DRIFT_CORRECTION_Z "drift_velocity_correction_z"

typedef struct plab_pass_view {
    uint32_t size; /* sizeof(plab_pass_view), set by the host */
    uint32_t dim;
    uint32_t body_count;
    double dt;
    double time;
    const double* position;  /* 3*body_count */
    const double* velocity;  /* 3*body_count */
    const double* force;     /* 3*body_count, contact + applied, N */
    const double* radius;
    const double* mass;
    const int32_t* group;    /* group index per body */
    /* fields the pass declared (`fields`), in that order, writable */
    double* const* fields;
    /* active contacts of every model after the latest force-displacement:
     * body index pairs; contact_end2_is_wall[k] != 0 for ball–wall */
    uint32_t contact_count;
    const int32_t* contact_end1;
    const int32_t* contact_end2;
    const uint8_t* contact_end2_is_wall;
    /* a pass that returns PLAB_PASS_UNSTABLE writes one line
     * here, "QUANTITY: which body, the value against its bound; likely
     * cause: ..." (NUL-terminated, at most diagnostic_capacity bytes
     * including the NUL). Name a body as
     * "ball index N", N its index in this view: the host replaces that with
     * the ball's id and group, which is how the user knows it. */
    char* diagnostic;
    uint32_t diagnostic_capacity;
    /* |x(contact_end2) - x(contact_end1)| of each listed
     * contact, m (for a ball–wall contact the ball centre's distance to the
     * wall), as the host's range test computed it at the current positions;
     * NULL when the host has none for this list (e.g. a pass phase after the
     * positions moved): then compute it from `position`. Read it only when
     * not NULL. */
    const double* contact_distance;
    /* ABI 2.4: the periodic cell's length along each axis, m (3 doubles;
     * 0 along an axis that is not periodic); NULL when no axis is. A pass
     * that takes the vector between two contact ends from `position` takes
     * its minimum image: d -= L round(d / L) along each periodic axis
     * (plab::minimum_image, pass.hpp). Read it only when `size` says the
     * host wrote it. */
    const double* periodic_length;
} plab_pass_view;

/* Return codes of plab_pass_desc.run: 0 success; PLAB_PASS_UNSTABLE the
 * state is unphysical (see plab_pass_view.diagnostic); any
 * other non-zero value a failure of the pass itself. */
#define PLAB_PASS_UNSTABLE 3

typedef struct plab_pass_desc {
    uint32_t size;           /* sizeof(plab_pass_desc) */
    const char* name;
    const char* doc;
    uint32_t phase;
    uint32_t stage;          /* order within the phase (lower first) */
    uint32_t property_count;
    const plab_property_desc* properties;
    uint32_t field_count;    /* per-body fields this pass owns or uses */
    const plab_field_desc* fields;
    void* (*create)(const double* props);
    void (*destroy)(void* state);
    int (*run)(void* state, const double* props, const plab_pass_view* view);
    /* ABI 2.1: as plab_contact_model_desc.material; a scene's pass names the
     * scene material it takes the values from ("material": "water") */
    const char* material;
} plab_pass_desc;

/* ---- private state of a pass, for checkpoints (optional) ---------------- */

/* A pass whose instance keeps state from one cycle to the next (e.g. "the
 * initial density is set") registers these so a checkpoint can carry it; a
 * pass without them is taken to be stateless (its state is rebuilt from its
 * properties). Contact-model instances are const during compute() and need
 * none. The bytes are the pass's own format: it should begin them with its
 * own version number so a later build can load an older checkpoint or refuse. */
typedef struct plab_pass_state_hooks {
    uint32_t size;         /* sizeof(plab_pass_state_hooks) */
    const char* pass_name; /* a pass this library registered */
    /* Writes the state into out[0..capacity) and returns the bytes it needs;
     * the host calls again with a larger buffer when that exceeds capacity. */
    uint64_t (*save)(const void* state, unsigned char* out, uint64_t capacity);
    /* Restores from `size` bytes written by save(); returns 0, or non-zero
     * when it does not understand them (the host then refuses the checkpoint). */
    int (*load)(void* state, const unsigned char* data, uint64_t size);
} plab_pass_state_hooks;

/* ---- registration ------------------------------------------------------- */

/* The host hands a registrar to plab_plugin_init. The descriptions passed in
 * must stay valid while the library is loaded (static storage). Each call
 * returns 0 when accepted. */
typedef struct plab_registrar {
    uint32_t size; /* sizeof(plab_registrar), set by the host */
    void* host;
    int (*register_contact_model)(void* host, const plab_contact_model_desc* desc);
    int (*register_pass)(void* host, const plab_pass_desc* desc);
    int (*register_pass_state)(void* host, const plab_pass_state_hooks* hooks);
    int (*register_material)(void* host, const plab_material_desc* desc); /* ABI 2.1 */
} plab_registrar;

typedef uint32_t (*plab_plugin_abi_version_fn)(void);
typedef int (*plab_plugin_init_fn)(const plab_registrar* registrar);

#ifdef __cplusplus
}
#endif

#endif /* PLAB_ABI_H */
