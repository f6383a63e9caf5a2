/* The FMI calls common to FMI 2.0 and 3.0, on the generic model core.
 *
 * fmi2.c and fmi3.c are thin adapters: they translate their API's types
 * and statuses and call these functions, which do the work and log what
 * went wrong through the adapter's logger. Every function returns 0 on
 * success and 1 on an error (already logged).
 */
#ifndef JUDDER_INSTANCE_H
#define JUDDER_INSTANCE_H

#include <stddef.h>
#include "model.h"

typedef struct Instance Instance;
/* The adapter's logger: error = 0 for information, 1 for an error, 2
 * for a warning (an assert of level warning). */
typedef void (*InstanceLogger)(Instance *c, int error, const char *text);

struct Instance {
    Model model;
    char *name;
    InstanceLogger log;
};

void instance_log(Instance *c, int error, const char *format, ...);
/* name copied, model defaults set; 1 on failure (nothing left allocated) */
int instance_init(Instance *c, const char *name, InstanceLogger log);
void instance_free(Instance *c);
int instance_reset(Instance *c);
/* Co-Simulation tolerance (if defined and positive, at most 1e-3) and
 * start time */
void instance_setup(Instance *c, int tolerance_defined, double tolerance,
                    double start_time);
void instance_set_time(Instance *c, double time);
/* Real (FMI 2) or Float64 (FMI 3) values; kind names them in messages */
int instance_get(Instance *c, const unsigned vr[], size_t n, double value[],
                 const char *kind);
int instance_set(Instance *c, const unsigned vr[], size_t n,
                 const double value[]);
/* A call on a type the model has none of: fine for no variables */
int instance_no_variables(Instance *c, const char *call, size_t n);
int instance_not_supported(Instance *c, const char *call);
/* FMU state */
int instance_get_state(Instance *c, void **state);
int instance_set_state(Instance *c, const void *state);
void instance_free_state(void **state);
int instance_serialize(Instance *c, const void *state, char *bytes,
                       size_t size, const char *call);
int instance_deserialize(Instance *c, const char *bytes, size_t size,
                         void **state, const char *call);
int instance_directional(Instance *c, const unsigned z[], size_t nz,
                         const unsigned v[], size_t nv, const double seed[],
                         double result[], int adjoint);
/* Initialisation mode entered (fmi2EnterInitializationMode,
 * fmi3EnterInitializationMode): states, relations and discrete variables
 * of the initialisation, initial() true; whether its event iteration
 * converged is said when the mode is left (instance_start) */
void instance_initialize(Instance *c);
/* Initialisation done (fmi2ExitInitializationMode,
 * fmi3ExitInitializationMode): states and discrete variables at the
 * start */
int instance_start(Instance *c);
/* Event iteration (fmi2NewDiscreteStates, fmi3UpdateDiscreteStates);
 * 1 (logged) if it has not converged within MODEL_MAX_EVENT_ITERATIONS */
int instance_event(Instance *c, int *again, int *states_changed);
/* The model's assert(...) at the present time and states: each warning
 * violated logged (once until it holds again); 1 (logged, with the time)
 * if an assert of level error is violated */
int instance_check(Instance *c);
/* Model Exchange */
int instance_set_states(Instance *c, const double x[], size_t nx);
int instance_get_states(Instance *c, double x[], size_t nx);
int instance_derivatives(Instance *c, double dx[], size_t nx);
int instance_indicators(Instance *c, double z[], size_t nz);
void instance_nominals(double x[], size_t nx);
/* Co-Simulation: integrate from t over h (the time reached is
 * c->model.time, also after a failure) */
int instance_do_step(Instance *c, double t, double h);

#endif
