/* Generic model core: evaluation, variable access and the embedded
 * Dormand-Prince 5(4) integrator used for co-simulation. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "model.h"

#include "model_functions.h"

static const double parameter_defaults[MODEL_NPAR + 1] =
    MODEL_PARAMETER_DEFAULTS;
/* declared min and max of the parameters and inputs (+-inf if none) */
static const double parameter_min[MODEL_NPAR + 1] = MODEL_PARAMETER_MIN;
static const double parameter_max[MODEL_NPAR + 1] = MODEL_PARAMETER_MAX;
static const int when_relation[MODEL_NW + 1] = MODEL_WHEN_RELATION;
static const int discrete_boolean[MODEL_ND + 1] = MODEL_DISCRETE_BOOLEAN;
static const int assert_error[MODEL_NA + 1] = MODEL_ASSERT_ERROR;
static const char *const assert_messages[MODEL_NA + 1] =
    MODEL_ASSERT_MESSAGES;

static void at_zero(Model *m, const double *before, const double *r);

typedef int (*WorkSizes)(casadi_int *, casadi_int *, casadi_int *, casadi_int *);

int model_init(Model *m) {
    /* work arrays large enough for every generated function */
    static const WorkSizes functions[] = {
        MODEL_ODE_WORK, MODEL_OUTPUTS_WORK, MODEL_START_WORK,
        MODEL_CALCULATED_WORK, MODEL_INDICATORS_WORK, MODEL_RELATIONS_WORK,
        MODEL_REINIT_WORK, MODEL_DISCRETES_WORK, MODEL_JACOBIAN_WORK,
        MODEL_ASSERTS_WORK};
    casadi_int sz_arg = 0, sz_res = 0, sz_iw = 0, sz_w = 0, a, r, i, w;
    size_t k;
    memset(m, 0, sizeof(*m));
    memcpy(m->p, parameter_defaults, sizeof(m->p));
    m->relative_tolerance = MODEL_DEFAULT_TOLERANCE;
    for (k = 0; k < sizeof(functions) / sizeof(functions[0]); k++) {
        functions[k](&a, &r, &i, &w);
        if (a > sz_arg) sz_arg = a;
        if (r > sz_res) sz_res = r;
        if (i > sz_iw) sz_iw = i;
        if (w > sz_w) sz_w = w;
    }
    m->arg = calloc((size_t)sz_arg + 1, sizeof(*m->arg));
    m->res = calloc((size_t)sz_res + 1, sizeof(*m->res));
    m->iw = calloc((size_t)sz_iw + 1, sizeof(*m->iw));
    m->w = calloc((size_t)sz_w + 1, sizeof(*m->w));
    if (!m->arg || !m->res || !m->iw || !m->w) { model_free(m); return 1; }
    m->stale = 1;
    model_start(m);
    return 0;
}

void model_free(Model *m) {
    free(m->arg); free(m->res); free(m->iw); free(m->w);
    m->arg = NULL; m->res = NULL; m->iw = NULL; m->w = NULL;
}

static void relations_at(Model *m, double t, const double *x, double *r) {
    m->arg[0] = &t; m->arg[1] = x; m->arg[2] = m->p;
    m->res[0] = r;
    MODEL_RELATIONS(m->arg, m->res, m->iw, m->w, 0);
}

void model_hold_relations(Model *m) {
    relations_at(m, m->time, m->x, m->p + P_RELATIONS);
    m->stale = 1;
}

/* The discrete variables' equations at the present t, x and the values
 * held in p; 1 if a value changed (the new ones are held) */
static int update_discretes(Model *m) {
    double d[MODEL_ND + 1];
    int k, changed = 0;
    if (MODEL_ND == 0) return 0;
    m->arg[0] = &m->time; m->arg[1] = m->x; m->arg[2] = m->p;
    m->res[0] = d;
    MODEL_DISCRETES(m->arg, m->res, m->iw, m->w, 0);
    for (k = 0; k < MODEL_ND; k++) {
        if (d[k] != m->p[P_DISCRETES + k]) changed = 1;
        m->p[P_DISCRETES + k] = d[k];
    }
    m->stale = 1;
    return changed;
}

/* Rounds of the relations and the discrete equations at the present t,
 * x and pre(), at most `rounds`; 1 if they reach values that one more
 * round leaves unchanged. Where the discrete values hold and only
 * relations on their zero within rounding disagree with them (their
 * indicators within MODEL_ZERO_SCALE of zero, relative to 1 + the
 * largest), those relations' bands grow to cover their indicators, as
 * in at_zero, and the rounds go on: each then takes the value its
 * operator has at zero */
static int settle(Model *m, int rounds) {
    double r[MODEL_NR + 1], z[MODEL_NR + 1], largest;
    int k, j, changed = 1, discrete, rounding;
    for (j = 0; j < rounds && changed; j++) {
        relations_at(m, m->time, m->x, m->p + P_RELATIONS);
        discrete = update_discretes(m);
        relations_at(m, m->time, m->x, r);
        changed = discrete;
        for (k = 0; k < MODEL_NR; k++)
            if (r[k] != m->p[P_RELATIONS + k]) changed = 1;
        if (!changed || discrete) continue;
        model_indicators(m, z);
        largest = 0.0;
        for (k = 0; k < MODEL_NR; k++)
            if (fabs(z[k]) > largest) largest = fabs(z[k]);
        rounding = 1;
        for (k = 0; k < MODEL_NR; k++)
            if (r[k] != m->p[P_RELATIONS + k] &&
                    fabs(z[k]) > MODEL_ZERO_SCALE * (1.0 + largest))
                rounding = 0;
        if (!rounding) continue;
        for (k = 0; k < MODEL_NR; k++)
            if (r[k] != m->p[P_RELATIONS + k])
                m->p[P_ZEROS + k] += MODEL_ZERO_WIDEN * fabs(z[k]);
        m->stale = 1;
    }
    return !changed;
}

static int bits_set(unsigned long v) {
    int n = 0;
    for (; v; v >>= 1) n += (int)(v & 1);
    return n;
}

/* The discrete equations and the continuous ones they depend on as one
 * mixed system, where the rounds cycle: MSL's friction at a slip through
 * zero alternates startForward and startBackward, the sliding direction
 * each assumes making the other's relation true, and never tries the
 * stuck state that holds. Its solution is sought from the discrete
 * values reached, then from them with each combination of Booleans
 * flipped, fewest flips first (as a search over the Booleans of a mixed
 * system); 1 if one settles (its discrete values held), 0 if none does
 * (they are restored). The relations held are restored either way, so
 * that the event iteration sees those that changed (and fires their
 * when-clauses) in its next round. The Booleans searched are first
 * those the rounds of this instant changed (a model of many friction
 * elements, MSL's HeatLosses, has 21 Booleans), then all of them (the
 * stuck state of LossyGearDemo3 needs `locked`, which the cycle of
 * startForward and startBackward never changes) */
static int search_among(Model *m, int only_moved) {
    double reached[MODEL_ND + 1], relations[MODEL_NR + 1];
    double zeros[MODEL_NR + 1];
    int position[MODEL_ND + 1];
    int nb = 0, k, flips;
    unsigned long seed;
    for (k = 0; k < MODEL_ND; k++)
        if (discrete_boolean[k] && (m->moved[k] || !only_moved))
            position[nb++] = k;
    if (nb == 0 || nb > MODEL_SEARCH_BOOLEANS) return 0;
    memcpy(reached, m->p + P_DISCRETES, sizeof(double) * MODEL_ND);
    memcpy(relations, m->p + P_RELATIONS, sizeof(double) * MODEL_NR);
    memcpy(zeros, m->p + P_ZEROS, sizeof(double) * MODEL_NR);
    for (flips = 0; flips <= nb; flips++)
        for (seed = 0; seed < (1UL << nb); seed++) {
            if (bits_set(seed) != flips) continue;
            memcpy(m->p + P_DISCRETES, reached, sizeof(double) * MODEL_ND);
            memcpy(m->p + P_ZEROS, zeros, sizeof(double) * MODEL_NR);
            for (k = 0; k < nb; k++)
                if (seed >> k & 1)
                    m->p[P_DISCRETES + position[k]] =
                        1.0 - reached[position[k]];
            if (settle(m, MODEL_SEARCH_ROUNDS)) {
                memcpy(m->p + P_RELATIONS, relations,
                       sizeof(double) * MODEL_NR);
                m->stale = 1;
                return 1;
            }
        }
    memcpy(m->p + P_DISCRETES, reached, sizeof(double) * MODEL_ND);
    memcpy(m->p + P_RELATIONS, relations, sizeof(double) * MODEL_NR);
    memcpy(m->p + P_ZEROS, zeros, sizeof(double) * MODEL_NR);
    m->stale = 1;
    return 0;
}

static int search_mixed(Model *m) {
    return search_among(m, 1) || search_among(m, 0);
}

int model_initialize(Model *m) {
    double before[MODEL_NR + 1], after[MODEL_NR + 1];
    int k, again = 0;
    m->arg[0] = m->p;
    m->res[0] = m->x;
    MODEL_START(m->arg, m->res, m->iw, m->w, 0);
    if (MODEL_NI) m->p[P_INITIAL] = 1;
    model_hold_relations(m);
    if (MODEL_ND == 0) return 0;
    /* pre() at the start values */
    memcpy(m->p + P_DISCRETES, parameter_defaults + P_DISCRETES,
           sizeof(double) * 2 * MODEL_ND);
    again = 1;
    memset(m->flips, 0, sizeof(m->flips));
    memset(m->swing, 0, sizeof(m->swing));
    relations_at(m, m->time, m->x, before);
    for (k = 0; k < MODEL_MAX_EVENT_ITERATIONS && again; k++) {
        again = update_discretes(m);
        relations_at(m, m->time, m->x, after);
        at_zero(m, before, after);
        relations_at(m, m->time, m->x, before);
    }
    memset(m->flips, 0, sizeof(m->flips));
    return again;
}

int model_start(Model *m) {
    int again = model_initialize(m);
    if (MODEL_NI) m->p[P_INITIAL] = 0;
    m->stale = 1;
    if (again) return 1;
    if (MODEL_ND == 0 && MODEL_NI == 0) return 0;
    /* then the event iteration at the start time, initial() false, from
     * the values the initialisation reached */
    memcpy(m->p + P_PREVIOUS, m->p + P_DISCRETES, sizeof(double) * MODEL_ND);
    m->iterations = 0;
    do model_event(m, &again); while (again);   /* bounded by model_event */
    return m->iterations >= MODEL_MAX_EVENT_ITERATIONS;
}

void model_indicators(Model *m, double *z) {
    m->arg[0] = &m->time; m->arg[1] = m->x; m->arg[2] = m->p;
    m->res[0] = z;
    MODEL_INDICATORS(m->arg, m->res, m->iw, m->w, 0);
}

/* The relations that keep changing at this instant while their
 * indicators stay on zero within rounding at every round (a driving
 * torque that is exactly zero in MSL's LossyGear, computed +-1e-15 as
 * the Booleans it decides change the linear solve): each one's band in
 * p grows to cover its indicator, so it takes the value its operator
 * has at zero and keeps it. A relation whose indicator is large at one
 * of the rounds changes for a reason (the mixed systems of friction,
 * search_mixed) and is left alone. Constants in model.h */
static void at_zero(Model *m, const double *before, const double *r) {
    double z[MODEL_NR + 1], largest = 0.0;
    int k, changed = 0, grown = 0;
    for (k = 0; k < MODEL_NR; k++)
        if (r[k] != before[k]) { m->flips[k]++; changed = 1; }
    if (!changed) return;
    model_indicators(m, z);
    for (k = 0; k < MODEL_NR; k++) {
        if (fabs(z[k]) > largest) largest = fabs(z[k]);
        if (m->flips[k] && fabs(z[k]) > m->swing[k]) m->swing[k] = fabs(z[k]);
        if (m->flips[k] >= MODEL_ZERO_FLIPS) grown = 1;
    }
    if (!grown) return;
    for (k = 0; k < MODEL_NR; k++)
        if (m->flips[k] >= MODEL_ZERO_FLIPS &&
                m->swing[k] <= MODEL_ZERO_SCALE * (1.0 + largest)) {
            m->p[P_ZEROS + k] += MODEL_ZERO_WIDEN * m->swing[k];
            m->flips[k] = 0;
            m->swing[k] = 0.0;
            m->stale = 1;
        }
}

int model_event(Model *m, int *again) {
    double r[MODEL_NR + 1], fired[MODEL_NW + 1], x[MODEL_NX + 1];
    double d[MODEL_ND + 1];
    double *held = m->p + P_RELATIONS;
    int k, any = 0;
    if (m->iterations == 0) {   /* a new instant: one more of its burst */
        m->searched = 0;
        memset(m->flips, 0, sizeof(m->flips));
        memset(m->swing, 0, sizeof(m->swing));
        memset(m->moved, 0, sizeof(m->moved));
        if (m->time - m->burst_start >
                MODEL_ZENO_SPAN * (fabs(m->time) + 1.0)) {
            m->burst_start = m->time;
            m->burst_events = 0;
        }
        m->burst_events++;
    }
    relations_at(m, m->time, m->x, r);
    at_zero(m, held, r);
    relations_at(m, m->time, m->x, r);
    for (k = 0; k < MODEL_NW; k++) {
        fired[k] = r[when_relation[k]] > 0.5 && held[when_relation[k]] < 0.5;
        any |= fired[k] > 0.5;
    }
    for (k = 0; k < MODEL_NR; k++) held[k] = r[k];
    if (any) {
        m->arg[0] = &m->time; m->arg[1] = m->x; m->arg[2] = m->p;
        m->arg[3] = fired;
        m->res[0] = x;
        MODEL_REINIT(m->arg, m->res, m->iw, m->w, 0);
        memcpy(m->x, x, sizeof(double) * MODEL_NX);
    }
    memcpy(d, m->p + P_DISCRETES, sizeof(double) * MODEL_ND);
    *again = update_discretes(m);
    for (k = 0; k < MODEL_ND; k++)
        if (d[k] != m->p[P_DISCRETES + k]) m->moved[k] = 1;
    if (*again && m->iterations >= MODEL_SEARCH_AFTER && !m->searched) {
        m->searched = 1;   /* once an instant: a failed search is final */
        if (search_mixed(m)) *again = 0;
    }
    if (!*again && MODEL_ND > 0 &&
        memcmp(m->p + P_PREVIOUS, m->p + P_DISCRETES,
               sizeof(double) * MODEL_ND) != 0) {
        /* the discrete equations hold with these pre(): the next
         * iteration starts from the values reached */
        memcpy(m->p + P_PREVIOUS, m->p + P_DISCRETES,
               sizeof(double) * MODEL_ND);
        *again = 1;
    }
    relations_at(m, m->time, m->x, r);
    for (k = 0; k < MODEL_NR; k++) if (r[k] != held[k]) *again = 1;
    m->stale = 1;
    if (!*again) m->iterations = 0;
    else if (++m->iterations >= MODEL_MAX_EVENT_ITERATIONS) *again = 0;
    return any;
}

/* a[k] 1 if assert k is violated, then the values of the messages */
static double *asserts_at(Model *m, double *a) {
    m->arg[0] = &m->time; m->arg[1] = m->x; m->arg[2] = m->p;
    m->res[0] = a;
    MODEL_ASSERTS(m->arg, m->res, m->iw, m->w, 0);
    return a;
}

int model_assert_failed(Model *m) {
    double a[MODEL_ASSERT_SIZE + 1];
    int k;
    if (MODEL_NA == 0) return 0;
    asserts_at(m, a);
    for (k = 0; k < MODEL_NA; k++)
        if (assert_error[k] && a[k] > 0.5) return 1;
    return 0;
}

int model_assertion(Model *m, char *text, size_t size, int *error) {
    double a[MODEL_ASSERT_SIZE + 1];
    const double *value = a + MODEL_NA;
    int k, found = -1;
    if (MODEL_NA == 0 || size == 0) return 0;
    asserts_at(m, a);
    for (k = 0; k < MODEL_NA; k++) {
        const char *c;
        size_t used = 0;
        if (a[k] <= 0.5) { m->warned[k] = 0; }
        else if (found < 0 && (assert_error[k] || !m->warned[k])) {
            found = k;
            /* the message, %g replaced by its values in turn */
            for (c = assert_messages[k]; *c && used + 1 < size; c++) {
                if (c[0] == '%' && c[1] == 'g') {
                    used += (size_t)snprintf(text + used, size - used, "%g",
                                             *value++);
                    if (used >= size) used = size - 1;
                    c++;
                } else if (c[0] == '%' && c[1] == '%') {
                    text[used++] = '%';
                    c++;
                } else {
                    text[used++] = *c;
                }
            }
            text[used] = 0;
            *error = assert_error[k];
            if (!assert_error[k]) m->warned[k] = 1;
            continue;
        }
        /* past the values of a message not written */
        for (c = assert_messages[k]; *c; c++) {
            if (c[0] != '%' || !c[1]) continue;
            if (c[1] == 'g') value++;
            c++;
        }
    }
    return found >= 0;
}

int model_chattering(const Model *m) {
    return m->burst_events > MODEL_ZENO_EVENTS;
}

static void derivatives(Model *m, double t, const double *x, double *xdot) {
    m->arg[0] = &t; m->arg[1] = x; m->arg[2] = m->p;
    m->res[0] = xdot;
    MODEL_ODE(m->arg, m->res, m->iw, m->w, 0);
}

void model_evaluate(Model *m) {
    if (!m->stale) return;
    derivatives(m, m->time, m->x, m->xdot);
    m->arg[0] = &m->time; m->arg[1] = m->x; m->arg[2] = m->p;
    m->res[0] = m->y;
    MODEL_OUTPUTS(m->arg, m->res, m->iw, m->w, 0);
    m->arg[0] = m->p;
    m->res[0] = m->calculated;
    MODEL_CALCULATED(m->arg, m->res, m->iw, m->w, 0);
    m->stale = 0;
}

int model_get(Model *m, unsigned vr, double *value) {
    if (vr == 0) { *value = m->time; return 0; }
    if (vr < VR_DERIVATIVES) { *value = m->x[vr - VR_STATES]; return 0; }
    if (vr < VR_PARAMETERS) {
        model_evaluate(m); *value = m->xdot[vr - VR_DERIVATIVES]; return 0;
    }
    if (vr < VR_CALCULATED) { *value = m->p[vr - VR_PARAMETERS]; return 0; }
    if (vr < VR_OUTPUTS) {
        model_evaluate(m); *value = m->calculated[vr - VR_CALCULATED];
        return 0;
    }
    if (vr < VR_INPUTS) { model_evaluate(m); *value = m->y[vr - VR_OUTPUTS]; return 0; }
    if (vr < VR_INDICATORS) { *value = m->p[MODEL_NP + vr - VR_INPUTS]; return 0; }
    if (vr < VR_END) {
        double z[MODEL_NR + 1];
        model_indicators(m, z); *value = z[vr - VR_INDICATORS]; return 0;
    }
    return 1;
}

int model_set(Model *m, unsigned vr, double value, int parameters_only) {
    unsigned k;
    if (vr >= VR_PARAMETERS && vr < VR_CALCULATED) k = vr - VR_PARAMETERS;
    else if (vr >= VR_INPUTS && vr < VR_INDICATORS) k = MODEL_NP + vr - VR_INPUTS;
    else if (!parameters_only && vr >= VR_STATES && vr < VR_DERIVATIVES) {
        m->x[vr - VR_STATES] = value; m->stale = 1; return 0;
    } else return 1;
    if (!(value >= parameter_min[k] && value <= parameter_max[k])) return 2;
    m->p[k] = value; m->stale = 1; return 0;
}

void model_bounds(unsigned vr, double *low, double *high) {
    unsigned k = vr >= VR_INPUTS ? MODEL_NP + vr - VR_INPUTS : vr - VR_PARAMETERS;
    *low = parameter_min[k]; *high = parameter_max[k];
}

static int unknown_row(unsigned vr) {
    if (vr >= VR_DERIVATIVES && vr < VR_PARAMETERS) return (int)(vr - VR_DERIVATIVES);
    if (vr >= VR_OUTPUTS && vr < VR_OUTPUTS + MODEL_NYO)
        return MODEL_NX + (int)(vr - VR_OUTPUTS);
    return -1;
}

static int known_column(unsigned vr) {
    if (vr >= VR_STATES && vr < VR_DERIVATIVES) return (int)(vr - VR_STATES);
    if (vr >= VR_PARAMETERS && vr < VR_CALCULATED) return MODEL_NX + (int)(vr - VR_PARAMETERS);
    if (vr >= VR_INPUTS && vr < VR_INDICATORS) return MODEL_NX + MODEL_NP + (int)(vr - VR_INPUTS);
    return -1;
}

int model_directional(Model *m, const unsigned *unknowns, size_t nz,
                      const unsigned *knowns, size_t nv,
                      const double *seed, double *result, int adjoint) {
    enum { ROWS = MODEL_NX + MODEL_NYO };
    /* CasADi writes the Jacobian's structural nonzeros column by column:
     * its sparsity is {rows, columns, colind[columns + 1], row[nnz]},
     * or {rows, columns, 1} for a dense one */
    double jac[MODEL_JACOBIAN_NNZ > 0 ? MODEL_JACOBIAN_NNZ : 1];
    const casadi_int *sp = MODEL_JACOBIAN_SPARSITY(0);
    const casadi_int ncol = sp[1];
    const int dense = sp[2] == 1;
    const casadi_int *colind = sp + 2, *row = sp + 3 + ncol;
    size_t i, j;
    casadi_int k, start, stop;
    for (i = 0; i < nz; i++) if (unknown_row(unknowns[i]) < 0) return 1;
    for (j = 0; j < nv; j++) if (known_column(knowns[j]) < 0) return 1;
    m->arg[0] = &m->time; m->arg[1] = m->x; m->arg[2] = m->p;
    m->res[0] = jac;
    MODEL_JACOBIAN(m->arg, m->res, m->iw, m->w, 0);
    for (i = 0; i < (adjoint ? nv : nz); i++) result[i] = 0;
    for (j = 0; j < nv; j++) {
        int col = known_column(knowns[j]);
        start = dense ? (casadi_int)col * ROWS : colind[col];
        stop = dense ? start + ROWS : colind[col + 1];
        for (k = start; k < stop; k++) {
            casadi_int r = dense ? k - start : row[k];
            for (i = 0; i < nz; i++) {
                if (unknown_row(unknowns[i]) != r) continue;
                if (adjoint) result[j] += jac[k] * seed[i];
                else result[i] += jac[k] * seed[j];
            }
        }
    }
    return 0;
}

/* FMU state: the whole Model but its work arrays */
void model_copy_state(Model *to, const Model *from) {
    const double **arg = to->arg;
    double **res = to->res;
    long long *iw = to->iw;
    double *w = to->w;
    memcpy(to, from, sizeof(Model));
    to->arg = arg; to->res = res; to->iw = iw; to->w = w;
}

size_t model_serialized_size(void) {
    return sizeof(MODEL_GUID) + sizeof(Model);
}

void model_serialize(const Model *m, char *bytes) {
    Model copy;
    memcpy(&copy, m, sizeof(Model));
    copy.arg = NULL; copy.res = NULL; copy.iw = NULL; copy.w = NULL;
    memcpy(bytes, MODEL_GUID, sizeof(MODEL_GUID));
    memcpy(bytes + sizeof(MODEL_GUID), &copy, sizeof(Model));
}

int model_deserialize(Model *m, const char *bytes, size_t size) {
    Model copy;
    if (size != model_serialized_size() ||
        memcmp(bytes, MODEL_GUID, sizeof(MODEL_GUID)) != 0) return 1;
    memcpy(&copy, bytes + sizeof(MODEL_GUID), sizeof(Model));
    model_copy_state(m, &copy);
    return 0;
}

const char *model_state_name(int i) {
    static const char *names[MODEL_NX + 1] = MODEL_STATE_NAMES;
    return i >= 0 && i < MODEL_NX ? names[i] : "?";
}

int model_finite(Model *m) {
    int i;
    model_evaluate(m);
    for (i = 0; i < MODEL_NX; i++) if (!isfinite(m->xdot[i])) return i + 1;
    return 0;
}

/* Dormand-Prince 5(4) coefficients (Hairer, Norsett, Wanner, 1993). */
static const double C2 = 1.0/5, C3 = 3.0/10, C4 = 4.0/5, C5 = 8.0/9;
static const double A21 = 1.0/5;
static const double A31 = 3.0/40, A32 = 9.0/40;
static const double A41 = 44.0/45, A42 = -56.0/15, A43 = 32.0/9;
static const double A51 = 19372.0/6561, A52 = -25360.0/2187,
                    A53 = 64448.0/6561, A54 = -212.0/729;
static const double A61 = 9017.0/3168, A62 = -355.0/33, A63 = 46732.0/5247,
                    A64 = 49.0/176, A65 = -5103.0/18656;
static const double B1 = 35.0/384, B3 = 500.0/1113, B4 = 125.0/192,
                    B5 = -2187.0/6784, B6 = 11.0/84;
static const double E1 = 71.0/57600, E3 = -71.0/16695, E4 = 71.0/1920,
                    E5 = -17253.0/339200, E6 = 22.0/525, E7 = -1.0/40;

/* One Dormand-Prince step of size h from (t, x) with k1 = f(t, x):
 * xn, k7 = f(t + h, xn) and the scaled error norm. */
static double dp_step(Model *m, double t, const double *x, const double *k1,
                      double h, double *xn, double *k7) {
    enum { N = MODEL_NX + 1 };
    double k2[N], k3[N], k4[N], k5[N], k6[N], xs[N];
    double err = 0, rtol = m->relative_tolerance, atol = rtol;
    int i, n = MODEL_NX;
    for (i = 0; i < n; i++) xs[i] = x[i] + h * A21 * k1[i];
    derivatives(m, t + C2 * h, xs, k2);
    for (i = 0; i < n; i++) xs[i] = x[i] + h * (A31 * k1[i] + A32 * k2[i]);
    derivatives(m, t + C3 * h, xs, k3);
    for (i = 0; i < n; i++) xs[i] = x[i] + h * (A41 * k1[i] + A42 * k2[i] + A43 * k3[i]);
    derivatives(m, t + C4 * h, xs, k4);
    for (i = 0; i < n; i++) xs[i] = x[i] + h * (A51 * k1[i] + A52 * k2[i] + A53 * k3[i] + A54 * k4[i]);
    derivatives(m, t + C5 * h, xs, k5);
    for (i = 0; i < n; i++) xs[i] = x[i] + h * (A61 * k1[i] + A62 * k2[i] + A63 * k3[i] + A64 * k4[i] + A65 * k5[i]);
    derivatives(m, t + h, xs, k6);
    for (i = 0; i < n; i++) xn[i] = x[i] + h * (B1 * k1[i] + B3 * k3[i] + B4 * k4[i] + B5 * k5[i] + B6 * k6[i]);
    derivatives(m, t + h, xn, k7);
    for (i = 0; i < n; i++) {
        double e = h * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i] + E7 * k7[i]);
        double sc = atol + rtol * fmax(fabs(x[i]), fabs(xn[i]));
        err += (e / sc) * (e / sc);
    }
    return sqrt(err / n);
}

/* 1 if a relation at (t, x) differs from the value held since the last
 * event */
static int relations_changed(Model *m, double t, const double *x) {
    double r[MODEL_NR + 1];
    int k;
    if (MODEL_NR == 0) return 0;
    relations_at(m, t, x, r);
    for (k = 0; k < MODEL_NR; k++)
        if (r[k] != m->p[P_RELATIONS + k]) return 1;
    return 0;
}

int model_integrate(Model *m, double t_end) {
    enum { N = MODEL_NX + 1 };
    double k1[N], k7[N], xn[N];
    double t = m->time, h, rtol = m->relative_tolerance, atol;
    int i, n = MODEL_NX;
    if (n == 0) { m->time = t_end; m->stale = 1; return 0; }
    atol = rtol;
    h = (t_end - t) > 0 ? (t_end - t) : 0;
    derivatives(m, t, m->x, k1);
    {   /* initial step from the derivative scale */
        double d0 = 0, d1 = 0, sc;
        for (i = 0; i < n; i++) {
            sc = atol + rtol * fabs(m->x[i]);
            d0 += (m->x[i] / sc) * (m->x[i] / sc);
            d1 += (k1[i] / sc) * (k1[i] / sc);
        }
        d0 = sqrt(d0 / n); d1 = sqrt(d1 / n);
        if (d1 > 1e-15) { double h0 = 0.01 * (d0 > 1e-5 ? d0 : 1e-5) / d1; if (h0 < h) h = h0; }
        /* states all zero with a large derivative: start above the
         * smallest step, error control shrinks it if needed */
        if (h < 1e-12 * (fabs(t) + 1.0) && t_end - t > 1e-12 * (fabs(t) + 1.0))
            h = 1e-12 * (fabs(t) + 1.0);
    }
    while (t < t_end) {
        double err, factor;
        if (t + h > t_end || t + 1.01 * h >= t_end) h = t_end - t;
        err = dp_step(m, t, m->x, k1, h, xn, k7);
        if (!isfinite(err)) return 2;
        if (err <= 1.0 && relations_changed(m, t + h, xn)) {
            /* an event inside the step: the shortest step after which a
             * relation has changed, to 1e-13 s relative */
            double low = 0, high = h, xt[N], kt[N];
            int again, iteration;
            while (high - low > 1e-13 * (fabs(t) + 1.0)) {
                double middle = 0.5 * (low + high);
                dp_step(m, t, m->x, k1, middle, xt, kt);
                if (relations_changed(m, t + middle, xt)) high = middle;
                else low = middle;
            }
            dp_step(m, t, m->x, k1, high, xn, k7);
            t = (high == t_end - t) ? t_end : t + high;
            memcpy(m->x, xn, sizeof(double) * n);
            m->time = t;
            for (iteration = 0; iteration < MODEL_MAX_EVENT_ITERATIONS;
                 iteration++) {
                model_event(m, &again);
                if (!again) break;
            }
            if (m->iterations >= MODEL_MAX_EVENT_ITERATIONS) return 3;
            if (model_chattering(m)) return 4;
            if (model_assert_failed(m)) return 5;
            derivatives(m, t, m->x, k1);
            m->steps++;
            m->events++;
            continue;
        }
        if (err <= 1.0) {
            t += h;
            memcpy(m->x, xn, sizeof(double) * n);
            memcpy(k1, k7, sizeof(double) * n);
            m->steps++;
            if (MODEL_NA) {
                m->time = t;
                m->stale = 1;
                if (model_assert_failed(m)) return 5;
            }
        } else {
            m->rejected++;
        }
        factor = err > 0 ? 0.9 * pow(err, -0.2) : 5.0;
        if (factor > 5.0) factor = 5.0;
        if (factor < 0.2) factor = 0.2;
        h *= factor;
        if (err > 1.0 && h < 1e-14 * (fabs(t) + 1.0)) return 1;
    }
    m->time = t_end;
    m->stale = 1;
    return 0;
}
