/* FMI 2.0 Model Exchange and Co-Simulation on the generic model core.
 *
 * Model Exchange: the importer integrates der(x) = f(t, x, p).
 * Co-Simulation: fmi2DoStep integrates with the embedded Dormand-Prince
 * 5(4) of model.c under the tolerance of fmi2SetupExperiment (or the
 * model's default) and lands exactly on each communication point.
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fmi2Functions.h"
#include "model.h"

typedef struct {
    Model model;
    fmi2Type type;
    fmi2CallbackFunctions callbacks;
    char *name;
    int logging;
} Instance;

static void logmsg(Instance *c, fmi2Status status, const char *format, ...) {
    char text[512];
    va_list args;
    if (!c->callbacks.logger) return;
    va_start(args, format);
    vsnprintf(text, sizeof(text), format, args);
    va_end(args);
    c->callbacks.logger(c->callbacks.componentEnvironment, c->name, status,
                        status == fmi2OK ? "logAll" : "logStatusError", "%s",
                        text);
}

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean on, size_t n,
                               const fmi2String categories[]) {
    (void)n; (void)categories;
    ((Instance *)c)->logging = on;
    return fmi2OK;
}

fmi2Component fmi2Instantiate(fmi2String name, fmi2Type type, fmi2String guid,
                              fmi2String location,
                              const fmi2CallbackFunctions *callbacks,
                              fmi2Boolean visible, fmi2Boolean logging) {
    Instance *c;
    (void)location; (void)visible;
    if (!guid || strcmp(guid, MODEL_GUID) != 0) {
        if (callbacks && callbacks->logger)
            callbacks->logger(callbacks->componentEnvironment, name, fmi2Error,
                              "logStatusError", "wrong GUID %s, expected %s",
                              guid ? guid : "(null)", MODEL_GUID);
        return NULL;
    }
    c = calloc(1, sizeof(Instance));
    if (!c) return NULL;
    c->type = type;
    if (callbacks) c->callbacks = *callbacks;
    c->name = malloc(strlen(name ? name : "") + 1);
    if (c->name) strcpy(c->name, name ? name : "");
    c->logging = logging;
    if (!c->name || model_init(&c->model) != 0) {
        free(c->name); free(c);
        return NULL;
    }
    return c;
}

void fmi2FreeInstance(fmi2Component c) {
    Instance *inst = c;
    if (!inst) return;
    model_free(&inst->model);
    free(inst->name);
    free(inst);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined,
                               fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
    Instance *inst = c;
    (void)stopTimeDefined; (void)stopTime;
    if (toleranceDefined && tolerance > 0)
        inst->model.relative_tolerance = tolerance < 1e-3 ? tolerance : 1e-3;
    inst->model.time = startTime;
    inst->model.stale = 1;
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) { (void)c; return fmi2OK; }

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
    Instance *inst = c;
    model_start(&inst->model); /* states follow the parameters set */
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c) { (void)c; return fmi2OK; }

fmi2Status fmi2Reset(fmi2Component c) {
    Instance *inst = c;
    model_free(&inst->model);
    return model_init(&inst->model) == 0 ? fmi2OK : fmi2Fatal;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[],
                       size_t nvr, fmi2Real value[]) {
    Instance *inst = c;
    size_t i;
    for (i = 0; i < nvr; i++) {
        if (model_get(&inst->model, vr[i], &value[i]) != 0) {
            logmsg(inst, fmi2Error, "no Real variable with value reference %u", vr[i]);
            return fmi2Error;
        }
    }
    return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[],
                       size_t nvr, const fmi2Real value[]) {
    Instance *inst = c;
    size_t i;
    for (i = 0; i < nvr; i++) {
        int done = model_set(&inst->model, vr[i], value[i], 0);
        if (done == 2) {
            double low, high;
            model_bounds(vr[i], &low, &high);
            logmsg(inst, fmi2Error, "value %g of value reference %u is outside "
                   "its declared range [%g, %g]", value[i], vr[i], low, high);
            return fmi2Error;
        }
        if (done != 0) {
            logmsg(inst, fmi2Error, "value reference %u cannot be set", vr[i]);
            return fmi2Error;
        }
    }
    return fmi2OK;
}

#define NO_VARIABLES(name, type) \
    fmi2Status name(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, type value[]) { \
        (void)vr; (void)value; if (nvr == 0) return fmi2OK; \
        logmsg(c, fmi2Error, "the model has no variables of this type"); return fmi2Error; }
NO_VARIABLES(fmi2GetInteger, fmi2Integer)
NO_VARIABLES(fmi2GetBoolean, fmi2Boolean)
NO_VARIABLES(fmi2GetString, fmi2String)
NO_VARIABLES(fmi2SetInteger, const fmi2Integer)
NO_VARIABLES(fmi2SetBoolean, const fmi2Boolean)
NO_VARIABLES(fmi2SetString, const fmi2String)

#define NOT_SUPPORTED(call) \
    { (void)c; logmsg(c, fmi2Error, call " is not supported"); return fmi2Error; }
fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *s) {
    Instance *inst = c;
    Model *copy = *s ? (Model *)*s : calloc(1, sizeof(Model));
    if (!copy) return fmi2Error;
    model_copy_state(copy, &inst->model);
    *s = copy;
    return fmi2OK;
}
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate s) {
    if (!s) return fmi2Error;
    model_copy_state(&((Instance *)c)->model, (const Model *)s);
    return fmi2OK;
}
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *s) {
    (void)c;
    if (s) { free(*s); *s = NULL; }
    return fmi2OK;
}
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate s, size_t *n) {
    (void)c; (void)s; *n = model_serialized_size(); return fmi2OK;
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate s, fmi2Byte b[], size_t n) {
    if (!s || n < model_serialized_size()) {
        logmsg(c, fmi2Error, "fmi2SerializeFMUstate: %zu bytes given, %zu needed",
               n, model_serialized_size());
        return fmi2Error;
    }
    model_serialize((const Model *)s, b);
    return fmi2OK;
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte b[], size_t n, fmi2FMUstate *s) {
    Model *copy = calloc(1, sizeof(Model));
    if (!copy) return fmi2Error;
    if (model_deserialize(copy, b, n) != 0) {
        free(copy);
        logmsg(c, fmi2Error, "fmi2DeSerializeFMUstate: not a state of this FMU");
        return fmi2Error;
    }
    *s = copy;
    return fmi2OK;
}
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference z[], size_t nz,
        const fmi2ValueReference v[], size_t nv, const fmi2Real dv[], fmi2Real dz[]) {
    if (model_directional(&((Instance *)c)->model, z, nz, v, nv, dv, dz, 0) != 0) {
        logmsg(c, fmi2Error, "fmi2GetDirectionalDerivative: the unknowns must be "
               "derivatives or outputs, the knowns states, parameters or inputs");
        return fmi2Error;
    }
    return fmi2OK;
}

/* Model Exchange */
fmi2Status fmi2EnterEventMode(fmi2Component c) { (void)c; return fmi2OK; }

fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo *info) {
    Instance *inst = c;
    int again = 0, changed = model_event(&inst->model, &again);
    info->newDiscreteStatesNeeded = again ? fmi2True : fmi2False;
    info->terminateSimulation = fmi2False;
    info->nominalsOfContinuousStatesChanged = fmi2False;
    info->valuesOfContinuousStatesChanged = changed ? fmi2True : fmi2False;
    info->nextEventTimeDefined = fmi2False;
    info->nextEventTime = 0;
    return fmi2OK;
}

fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c) { (void)c; return fmi2OK; }

fmi2Status fmi2CompletedIntegratorStep(fmi2Component c, fmi2Boolean noSet,
                                       fmi2Boolean *enterEventMode,
                                       fmi2Boolean *terminate) {
    (void)c; (void)noSet;
    *enterEventMode = fmi2False;
    *terminate = fmi2False;
    return fmi2OK;
}

fmi2Status fmi2SetTime(fmi2Component c, fmi2Real time) {
    Instance *inst = c;
    inst->model.time = time;
    inst->model.stale = 1;
    return fmi2OK;
}

fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real x[], size_t nx) {
    Instance *inst = c;
    if (nx != MODEL_NX) return fmi2Error;
    memcpy(inst->model.x, x, sizeof(double) * nx);
    inst->model.stale = 1;
    return fmi2OK;
}

fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real dx[], size_t nx) {
    Instance *inst = c;
    if (nx != MODEL_NX) return fmi2Error;
    model_evaluate(&inst->model);
    memcpy(dx, inst->model.xdot, sizeof(double) * nx);
    if (model_finite(&inst->model) != 0) {
        logmsg(inst, fmi2Error, "der(%s) is not finite at t = %g (check the "
               "parameters)", model_state_name(model_finite(&inst->model) - 1),
               inst->model.time);
        return fmi2Error;
    }
    return fmi2OK;
}

fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real z[], size_t nz) {
    if (nz != MODEL_NR) return fmi2Error;
    if (nz) model_indicators(&((Instance *)c)->model, z);
    return fmi2OK;
}

fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real x[], size_t nx) {
    Instance *inst = c;
    if (nx != MODEL_NX) return fmi2Error;
    memcpy(x, inst->model.x, sizeof(double) * nx);
    return fmi2OK;
}

fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real x[], size_t nx) {
    size_t i;
    (void)c;
    for (i = 0; i < nx; i++) x[i] = 1.0;
    return fmi2OK;
}

/* Co-Simulation */
fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[],
        size_t nvr, const fmi2Integer order[], const fmi2Real value[]) {
    (void)vr; (void)order; (void)value;
    if (nvr == 0) return fmi2OK;
    NOT_SUPPORTED("fmi2SetRealInputDerivatives")
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[],
        size_t nvr, const fmi2Integer order[], fmi2Real value[]) {
    (void)vr; (void)order; (void)value;
    if (nvr == 0) return fmi2OK;
    NOT_SUPPORTED("fmi2GetRealOutputDerivatives")
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean noSetPrior) {
    Instance *inst = c;
    (void)noSetPrior;
    if (h < 0) return fmi2Error;
    inst->model.time = t;
    switch (model_integrate(&inst->model, t + h)) {
    case 0: break;
    case 2:
        logmsg(inst, fmi2Error, "the derivatives are not finite in the step "
               "from t = %g (check the parameters)", inst->model.time);
        return fmi2Error;
    default:
        logmsg(inst, fmi2Error, "the integrator failed at t = %g (step size too small)",
               inst->model.time);
        return fmi2Error;
    }
    return fmi2OK;
}

fmi2Status fmi2CancelStep(fmi2Component c) { NOT_SUPPORTED("fmi2CancelStep") }

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *v) {
    (void)s; (void)v; NOT_SUPPORTED("fmi2GetStatus") }

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *v) {
    Instance *inst = c;
    if (s == fmi2LastSuccessfulTime) { *v = inst->model.time; return fmi2OK; }
    return fmi2Discard;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *v) {
    (void)s; (void)v; NOT_SUPPORTED("fmi2GetIntegerStatus") }

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *v) {
    (void)s; (void)v; NOT_SUPPORTED("fmi2GetBooleanStatus") }

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *v) {
    (void)s; (void)v; NOT_SUPPORTED("fmi2GetStringStatus") }
