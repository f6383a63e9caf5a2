/* FMI 2.0 Model Exchange and Co-Simulation: an adapter of the calls
 * common to FMI 2 and 3 (instance.c) to the FMI 2.0 API.
 *
 * Model Exchange: the importer integrates der(x) = f(t, x, p).
 * Co-Simulation: fmi2DoStep integrates with the embedded Dormand-Prince
 * 5(4) of model.c under the tolerance of fmi2SetupExperiment (or the
 * model's default) and lands exactly on each communication point.
 */
#include <stdlib.h>
#include <string.h>
#include "fmi2Functions.h"
#include "instance.h"

typedef struct {
    Instance core;             /* first: an Fmi2 is an Instance */
    fmi2CallbackFunctions callbacks;
    int logging;
} Fmi2;

#define CORE(c) ((Instance *)(c))
#define STATUS(failed) ((failed) ? fmi2Error : fmi2OK)

static void fmi2_log(Instance *core, int error, const char *text) {
    Fmi2 *c = (Fmi2 *)core;
    if (!c->callbacks.logger) return;
    c->callbacks.logger(c->callbacks.componentEnvironment, core->name,
                        error == 1 ? fmi2Error : error ? fmi2Warning : fmi2OK,
                        error == 1 ? "logStatusError" : error ?
                        "logStatusWarning" : "logAll", "%s", text);
}

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean on, size_t n,
                               const fmi2String categories[]) {
    (void)n; (void)categories;
    ((Fmi2 *)c)->logging = on;
    return fmi2OK;
}

fmi2Component fmi2Instantiate(fmi2String name, fmi2Type type, fmi2String guid,
                              fmi2String location,
                              const fmi2CallbackFunctions *callbacks,
                              fmi2Boolean visible, fmi2Boolean logging) {
    Fmi2 *c;
    (void)type; (void)location; (void)visible;
    if (!guid || strcmp(guid, MODEL_GUID) != 0) {
        if (callbacks && callbacks->logger)
            callbacks->logger(callbacks->componentEnvironment, name, fmi2Error,
                              "logStatusError", "wrong GUID %s, expected %s",
                              guid ? guid : "(null)", MODEL_GUID);
        return NULL;
    }
    c = calloc(1, sizeof(Fmi2));
    if (!c) return NULL;
    if (callbacks) c->callbacks = *callbacks;
    c->logging = logging;
    if (instance_init(&c->core, name, fmi2_log) != 0) {
        free(c);
        return NULL;
    }
    return c;
}

void fmi2FreeInstance(fmi2Component c) {
    if (!c) return;
    instance_free(CORE(c));
    free(c);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined,
                               fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
    (void)stopTimeDefined; (void)stopTime;
    instance_setup(CORE(c), toleranceDefined, tolerance, startTime);
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
    /* values with initial() true until the mode is left */
    instance_initialize(CORE(c));
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
    /* states and discrete variables follow the parameters set */
    return STATUS(instance_start(CORE(c)));
}

fmi2Status fmi2Terminate(fmi2Component c) { (void)c; return fmi2OK; }

fmi2Status fmi2Reset(fmi2Component c) {
    return instance_reset(CORE(c)) ? fmi2Fatal : fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[],
                       size_t nvr, fmi2Real value[]) {
    return STATUS(instance_get(CORE(c), vr, nvr, value, "Real"));
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[],
                       size_t nvr, const fmi2Real value[]) {
    return STATUS(instance_set(CORE(c), vr, nvr, value));
}

#define NO_VARIABLES(name, type) \
    fmi2Status name(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, type value[]) { \
        (void)vr; (void)value; return STATUS(instance_no_variables(CORE(c), #name, nvr)); }
NO_VARIABLES(fmi2GetInteger, fmi2Integer)
NO_VARIABLES(fmi2GetBoolean, fmi2Boolean)
NO_VARIABLES(fmi2GetString, fmi2String)
NO_VARIABLES(fmi2SetInteger, const fmi2Integer)
NO_VARIABLES(fmi2SetBoolean, const fmi2Boolean)
NO_VARIABLES(fmi2SetString, const fmi2String)

#define NOT_SUPPORTED(call) { return STATUS(instance_not_supported(CORE(c), call)); }

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *s) {
    return STATUS(instance_get_state(CORE(c), s));
}
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate s) {
    return STATUS(instance_set_state(CORE(c), s));
}
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *s) {
    (void)c; instance_free_state(s); return fmi2OK;
}
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate s, size_t *n) {
    (void)c; (void)s; *n = model_serialized_size(); return fmi2OK;
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate s, fmi2Byte b[], size_t n) {
    return STATUS(instance_serialize(CORE(c), s, b, n, "fmi2SerializeFMUstate"));
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte b[], size_t n, fmi2FMUstate *s) {
    return STATUS(instance_deserialize(CORE(c), b, n, s, "fmi2DeSerializeFMUstate"));
}
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference z[], size_t nz,
        const fmi2ValueReference v[], size_t nv, const fmi2Real dv[], fmi2Real dz[]) {
    return STATUS(instance_directional(CORE(c), z, nz, v, nv, dv, dz, 0));
}

/* Model Exchange */
fmi2Status fmi2EnterEventMode(fmi2Component c) { (void)c; return fmi2OK; }

fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo *info) {
    int again, changed;
    int failed = instance_event(CORE(c), &again, &changed);
    info->newDiscreteStatesNeeded = again ? fmi2True : fmi2False;
    info->terminateSimulation = fmi2False;
    info->nominalsOfContinuousStatesChanged = fmi2False;
    info->valuesOfContinuousStatesChanged = changed ? fmi2True : fmi2False;
    info->nextEventTimeDefined = fmi2False;
    info->nextEventTime = 0;
    return STATUS(failed);
}

fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c) { (void)c; return fmi2OK; }

fmi2Status fmi2CompletedIntegratorStep(fmi2Component c, fmi2Boolean noSet,
                                       fmi2Boolean *enterEventMode,
                                       fmi2Boolean *terminate) {
    (void)noSet;
    *enterEventMode = fmi2False;
    *terminate = fmi2False;
    return STATUS(instance_check(CORE(c)));   /* the model's asserts */
}

fmi2Status fmi2SetTime(fmi2Component c, fmi2Real time) {
    instance_set_time(CORE(c), time);
    return fmi2OK;
}

fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real x[], size_t nx) {
    return STATUS(instance_set_states(CORE(c), x, nx));
}

fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real dx[], size_t nx) {
    return STATUS(instance_derivatives(CORE(c), dx, nx));
}

fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real z[], size_t nz) {
    return STATUS(instance_indicators(CORE(c), z, nz));
}

fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real x[], size_t nx) {
    return STATUS(instance_get_states(CORE(c), x, nx));
}

fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real x[], size_t nx) {
    (void)c; instance_nominals(x, nx); return fmi2OK;
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
    (void)noSetPrior;
    return STATUS(instance_do_step(CORE(c), t, h));
}

fmi2Status fmi2CancelStep(fmi2Component c) { NOT_SUPPORTED("fmi2CancelStep") }

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *v) {
    (void)s; (void)v; NOT_SUPPORTED("fmi2GetStatus") }

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *v) {
    if (s == fmi2LastSuccessfulTime) { *v = CORE(c)->model.time; return fmi2OK; }
    return fmi2Discard;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *v) {
    (void)s; (void)v; NOT_SUPPORTED("fmi2GetIntegerStatus") }

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *v) {
    (void)s; (void)v; NOT_SUPPORTED("fmi2GetBooleanStatus") }

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *v) {
    (void)s; (void)v; NOT_SUPPORTED("fmi2GetStringStatus") }
