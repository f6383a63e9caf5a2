/* Generic model core of the project's FMUs.
 *
 * Nothing here knows a model: sizes, defaults and the equations come from
 * the generated files model_config.h and model_functions.c (CasADi code of
 * der(x) = f(t, x, p), y = h(t, x, p) and x0 = s(p), written by the
 * back end from the Modelica source).
 */
#ifndef JUDDER_MODEL_H
#define JUDDER_MODEL_H

#include <stddef.h>
#include "model_config.h"

/* Value references: 0 time, then states, derivatives, parameters,
 * calculated parameters, outputs and the model's other variables (y:
 * MODEL_NYO outputs, then the locals, MODEL_NY in all) and inputs, in this
 * order. Inputs are stored after the parameters in p. */
#define VR_STATES 1
#define VR_DERIVATIVES (VR_STATES + MODEL_NX)
#define VR_PARAMETERS (VR_DERIVATIVES + MODEL_NX)
#define VR_CALCULATED (VR_PARAMETERS + MODEL_NP)
#define VR_OUTPUTS (VR_CALCULATED + MODEL_NC)
#define VR_INPUTS (VR_OUTPUTS + MODEL_NY)
#define VR_INDICATORS (VR_INPUTS + MODEL_NU)
#define VR_END (VR_INDICATORS + MODEL_NR)
/* p holds the parameters, the inputs and, held between events, the
 * values of the relations that generate events, the discrete (Integer
 * and Boolean) variables, their pre() and initial() (MODEL_NI = 1 if the
 * equations use it) */
#define P_RELATIONS (MODEL_NP + MODEL_NU)
#define P_DISCRETES (P_RELATIONS + MODEL_NR)
#define P_PREVIOUS (P_DISCRETES + MODEL_ND)
#define P_INITIAL (P_PREVIOUS + MODEL_ND)
/* then each relation's rounding band, 0 until the relation is found on
 * its zero (model.c, at_zero) */
#define P_ZEROS (P_INITIAL + MODEL_NI)
#define MODEL_NPAR (P_ZEROS + MODEL_NR)
/* Event iterations allowed at one instant */
#define MODEL_MAX_EVENT_ITERATIONS 100
/* Rounds at one instant after which a round that changes the discrete
 * values starts the search of the mixed system, once an instant (model.c,
 * search_mixed): the Booleans it flips (a model with more is not
 * searched), the rounds it gives each start to settle */
#define MODEL_SEARCH_AFTER 10
#define MODEL_SEARCH_BOOLEANS 12
#define MODEL_SEARCH_ROUNDS 20
/* A relation that changes at MODEL_ZERO_FLIPS rounds of one instant
 * while its indicator stays within MODEL_ZERO_SCALE of zero (relative to
 * 1 + the largest indicator) is on its zero within rounding: its band
 * grows to MODEL_ZERO_WIDEN times the indicator, and it keeps the value
 * its operator has at zero (>= and <= true, > and < false) */
#define MODEL_ZERO_FLIPS 3
#define MODEL_ZERO_SCALE 1e-12
#define MODEL_ZERO_WIDEN 4.0
/* A model chatters (Zeno) when more than MODEL_ZENO_EVENTS events come
 * within MODEL_ZENO_SPAN * (|t| + 1) seconds: a relation that switches
 * back at once (a relay on its own output) would otherwise hold the
 * importer for ever, each event a step of the event location's size */
#define MODEL_ZENO_EVENTS 1000
#define MODEL_ZENO_SPAN 1e-9

typedef struct {
    double time;
    double x[MODEL_NX + 1];
    double p[MODEL_NPAR + 1];
    double xdot[MODEL_NX + 1];
    double y[MODEL_NY + 1];
    double calculated[MODEL_NC + 1];
    int stale;                 /* xdot, y, calculated need evaluating */
    int iterations;            /* event iterations at this instant so far */
    int searched;              /* the mixed system searched at this instant */
    double relative_tolerance; /* co-simulation integrator */
    long steps, rejected, events; /* co-simulation statistics */
    double burst_start;        /* time of the first event of a burst */
    long burst_events;         /* events since (see MODEL_ZENO_EVENTS) */
    int warned[MODEL_NA + 1];  /* a warning assert said, not yet holding */
    int flips[MODEL_NR + 1];   /* changes of each relation at this instant */
    double swing[MODEL_NR + 1]; /* the largest |indicator| since it changed */
    int moved[MODEL_ND + 1];   /* discrete values changed at this instant */
    /* CasADi work arrays */
    const double **arg;
    double **res;
    long long *iw;
    double *w;
} Model;

int model_init(Model *m);            /* defaults; 0 on success */
void model_free(Model *m);
/* The initialisation, left with initial() true: x = x0(p), the
 * relations at x, the discrete variables' equations with pre() at the
 * start values until they hold; returns 1 if they do not */
int model_initialize(Model *m);
/* model_initialize, then initial() false and the event iteration at the
 * start time; returns 1 if either did not converge */
int model_start(Model *m);
void model_evaluate(Model *m);       /* xdot, y, calculated from t, x, p */
int model_get(Model *m, unsigned vr, double *value);
/* 0 on success, 1 if vr cannot be set, 2 if value is outside the
 * declared min and max (then nothing changes) */
int model_set(Model *m, unsigned vr, double value, int parameters_only);
void model_bounds(unsigned vr, double *low, double *high);
/* 0 if every derivative is finite, else 1 + index of the first that is not */
int model_finite(Model *m);
/* Event indicators z (MODEL_NR of them) at the present t, x */
void model_indicators(Model *m, double *z);
/* Event iteration at the present t, x: fire the when-clauses whose
 * relation became true (reinit), hold the new relation values, then
 * evaluate the discrete variables' equations; once they no longer
 * change, pre() takes their values. Returns 1 if the states changed;
 * *again is set if the relations changed once more after the reinit or
 * a discrete variable or its pre() changed (another iteration is
 * needed), unless MODEL_MAX_EVENT_ITERATIONS have been made at this
 * instant: then m->iterations is that number (not converged). */
int model_event(Model *m, int *again);
/* 1 if more than MODEL_ZENO_EVENTS instants with an event came within
 * MODEL_ZENO_SPAN * (|t| + 1) s of one another (counted by model_event) */
int model_chattering(const Model *m);
/* The model's assert(...) at the present t, x: 0 if none is violated
 * that is still to be said, else 1 with "FILE:LINE: message" in text
 * and *error 1 for an error, 0 for a warning (said once: not again
 * until its condition has held) */
int model_assertion(Model *m, char *text, size_t size, int *error);
/* 1 if an assert of level error is violated at the present t, x */
int model_assert_failed(Model *m);
/* Relation values at the present t, x, without firing (initialisation) */
void model_hold_relations(Model *m);
const char *model_state_name(int i);   /* Modelica name of state i */
/* Directional derivatives from the Jacobian of [der(x); y] with respect
 * to [x; parameters; inputs] (CasADi AD). adjoint = 0: dz = J dv for the
 * unknowns z and knowns v given by value references; adjoint = 1:
 * dv = J^T dz. Returns 1 on a value reference that is not an unknown
 * (derivative, output) or a known (state, parameter, input). */
int model_directional(Model *m, const unsigned *unknowns, size_t nz,
                      const unsigned *knowns, size_t nv,
                      const double *seed, double *result, int adjoint);
/* FMU state: copy everything but the work arrays; serialise with the
 * GUID in front (the same binary restores it) */
void model_copy_state(Model *to, const Model *from);
size_t model_serialized_size(void);
void model_serialize(const Model *m, char *bytes);
int model_deserialize(Model *m, const char *bytes, size_t size); /* 0: ok */
/* Advance from m->time to t_end with Dormand-Prince 5(4) under
 * relative_tolerance; returns 0 on success, 1 if the step size became
 * too small, 2 if the derivatives are not finite, 3 if an event
 * iteration did not converge, 4 if the model chatters, 5 if an assert
 * of level error failed after a step or an event (m->time is there). Relations that change
 * inside a step are located (bisection on the step size) and handled
 * as events there. */
int model_integrate(Model *m, double t_end);

#endif
