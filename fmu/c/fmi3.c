/* FMI 3.0 Model Exchange and Co-Simulation on the generic model core.
 * Only Float64 variables exist; the other types and clocks report an
 * error. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fmi3Functions.h"
#include "model.h"

typedef struct {
    Model model;
    fmi3InstanceEnvironment environment;
    fmi3LogMessageCallback log;
    char *name;
    int cosimulation;
} Instance;

static void logmsg(Instance *c, fmi3Status status, const char *format, ...) {
    char text[512];
    va_list args;
    if (!c || !c->log) return;
    va_start(args, format);
    vsnprintf(text, sizeof(text), format, args);
    va_end(args);
    c->log(c->environment, status,
           status == fmi3OK ? "logAll" : "logStatusError", text);
}

const char *fmi3GetVersion(void) { return fmi3Version; }

fmi3Status fmi3SetDebugLogging(fmi3Instance c, fmi3Boolean on, size_t n,
                               const fmi3String categories[]) {
    (void)c; (void)on; (void)n; (void)categories;
    return fmi3OK;
}

static fmi3Instance instantiate(fmi3String name, fmi3String token,
        fmi3InstanceEnvironment environment, fmi3LogMessageCallback log,
        int cosimulation) {
    Instance *c;
    if (!token || strcmp(token, MODEL_GUID) != 0) {
        if (log) log(environment, fmi3Error, "logStatusError",
                     "wrong instantiation token");
        return NULL;
    }
    c = calloc(1, sizeof(Instance));
    if (!c) return NULL;
    c->environment = environment;
    c->log = log;
    c->cosimulation = cosimulation;
    c->name = malloc(strlen(name ? name : "") + 1);
    if (c->name) strcpy(c->name, name ? name : "");
    if (!c->name || model_init(&c->model) != 0) {
        free(c->name); free(c);
        return NULL;
    }
    return c;
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String name, fmi3String token,
        fmi3String resources, fmi3Boolean visible, fmi3Boolean logging,
        fmi3InstanceEnvironment environment, fmi3LogMessageCallback log) {
    (void)resources; (void)visible; (void)logging;
    return instantiate(name, token, environment, log, 0);
}

/* Co-Simulation: fmi3DoStep integrates with the embedded Dormand-Prince
 * 5(4), events located inside the step; no event mode, no early return */
fmi3Instance fmi3InstantiateCoSimulation(fmi3String name, fmi3String token,
        fmi3String resources, fmi3Boolean visible, fmi3Boolean logging,
        fmi3Boolean eventMode, fmi3Boolean earlyReturn,
        const fmi3ValueReference required[], size_t nRequired,
        fmi3InstanceEnvironment environment, fmi3LogMessageCallback log,
        fmi3IntermediateUpdateCallback update) {
    (void)resources; (void)visible; (void)logging; (void)eventMode;
    (void)earlyReturn; (void)required; (void)nRequired; (void)update;
    return instantiate(name, token, environment, log, 1);
}

fmi3Instance fmi3InstantiateScheduledExecution(fmi3String name,
        fmi3String token, fmi3String resources, fmi3Boolean visible,
        fmi3Boolean logging, fmi3InstanceEnvironment environment,
        fmi3LogMessageCallback log, fmi3ClockUpdateCallback clockUpdate,
        fmi3LockPreemptionCallback lock, fmi3UnlockPreemptionCallback unlock) {
    (void)name; (void)token; (void)resources; (void)visible; (void)logging;
    (void)clockUpdate; (void)lock; (void)unlock;
    if (log) log(environment, fmi3Error, "logStatusError",
                 "scheduled execution is not supported");
    return NULL;
}

void fmi3FreeInstance(fmi3Instance c) {
    Instance *inst = c;
    if (!inst) return;
    model_free(&inst->model);
    free(inst->name);
    free(inst);
}

fmi3Status fmi3EnterInitializationMode(fmi3Instance c, fmi3Boolean toleranceDefined,
        fmi3Float64 tolerance, fmi3Float64 startTime,
        fmi3Boolean stopTimeDefined, fmi3Float64 stopTime) {
    Instance *inst = c;
    (void)stopTimeDefined; (void)stopTime;
    if (inst->cosimulation && toleranceDefined && tolerance > 0)
        inst->model.relative_tolerance = tolerance < 1e-3 ? tolerance : 1e-3;
    inst->model.time = startTime;
    inst->model.stale = 1;
    return fmi3OK;
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance c) {
    model_start(&((Instance *)c)->model);
    return fmi3OK;
}

fmi3Status fmi3EnterEventMode(fmi3Instance c) { (void)c; return fmi3OK; }
fmi3Status fmi3Terminate(fmi3Instance c) { (void)c; return fmi3OK; }

fmi3Status fmi3Reset(fmi3Instance c) {
    Instance *inst = c;
    model_free(&inst->model);
    return model_init(&inst->model) == 0 ? fmi3OK : fmi3Fatal;
}

fmi3Status fmi3GetFloat64(fmi3Instance c, const fmi3ValueReference vr[],
                          size_t nvr, fmi3Float64 value[], size_t n) {
    Instance *inst = c;
    size_t i;
    if (n != nvr) return fmi3Error;
    for (i = 0; i < nvr; i++) {
        if (model_get(&inst->model, vr[i], &value[i]) != 0) {
            logmsg(inst, fmi3Error, "no Float64 variable with value reference %u", vr[i]);
            return fmi3Error;
        }
    }
    return fmi3OK;
}

fmi3Status fmi3SetFloat64(fmi3Instance c, const fmi3ValueReference vr[],
                          size_t nvr, const fmi3Float64 value[], size_t n) {
    Instance *inst = c;
    size_t i;
    if (n != nvr) return fmi3Error;
    for (i = 0; i < nvr; i++) {
        int done = model_set(&inst->model, vr[i], value[i], 0);
        if (done == 2) {
            double low, high;
            model_bounds(vr[i], &low, &high);
            logmsg(inst, fmi3Error, "value %g of value reference %u is outside "
                   "its declared range [%g, %g]", value[i], vr[i], low, high);
            return fmi3Error;
        }
        if (done != 0) {
            logmsg(inst, fmi3Error, "value reference %u cannot be set", vr[i]);
            return fmi3Error;
        }
    }
    return fmi3OK;
}

#define NO_VARIABLES(name, type) \
    fmi3Status name(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr, type value[], size_t n) { \
        (void)vr; (void)value; (void)n; if (nvr == 0) return fmi3OK; \
        logmsg(c, fmi3Error, #name ": the model has no variables of this type"); return fmi3Error; }
NO_VARIABLES(fmi3GetFloat32, fmi3Float32)
NO_VARIABLES(fmi3GetInt8, fmi3Int8)
NO_VARIABLES(fmi3GetUInt8, fmi3UInt8)
NO_VARIABLES(fmi3GetInt16, fmi3Int16)
NO_VARIABLES(fmi3GetUInt16, fmi3UInt16)
NO_VARIABLES(fmi3GetInt32, fmi3Int32)
NO_VARIABLES(fmi3GetUInt32, fmi3UInt32)
NO_VARIABLES(fmi3GetInt64, fmi3Int64)
NO_VARIABLES(fmi3GetUInt64, fmi3UInt64)
NO_VARIABLES(fmi3GetBoolean, fmi3Boolean)
NO_VARIABLES(fmi3GetString, fmi3String)
NO_VARIABLES(fmi3SetFloat32, const fmi3Float32)
NO_VARIABLES(fmi3SetInt8, const fmi3Int8)
NO_VARIABLES(fmi3SetUInt8, const fmi3UInt8)
NO_VARIABLES(fmi3SetInt16, const fmi3Int16)
NO_VARIABLES(fmi3SetUInt16, const fmi3UInt16)
NO_VARIABLES(fmi3SetInt32, const fmi3Int32)
NO_VARIABLES(fmi3SetUInt32, const fmi3UInt32)
NO_VARIABLES(fmi3SetInt64, const fmi3Int64)
NO_VARIABLES(fmi3SetUInt64, const fmi3UInt64)
NO_VARIABLES(fmi3SetBoolean, const fmi3Boolean)
NO_VARIABLES(fmi3SetString, const fmi3String)

#define NOT_SUPPORTED(call) \
    { logmsg(c, fmi3Error, call " is not supported"); return fmi3Error; }

fmi3Status fmi3GetBinary(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,
        size_t sizes[], fmi3Binary value[], size_t n) {
    (void)vr; (void)sizes; (void)value; (void)n; if (nvr == 0) return fmi3OK;
    NOT_SUPPORTED("fmi3GetBinary") }
fmi3Status fmi3SetBinary(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,
        const size_t sizes[], const fmi3Binary value[], size_t n) {
    (void)vr; (void)sizes; (void)value; (void)n; if (nvr == 0) return fmi3OK;
    NOT_SUPPORTED("fmi3SetBinary") }
fmi3Status fmi3GetClock(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr, fmi3Clock v[]) {
    (void)vr; (void)v; if (nvr == 0) return fmi3OK; NOT_SUPPORTED("fmi3GetClock") }
fmi3Status fmi3SetClock(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr, const fmi3Clock v[]) {
    (void)vr; (void)v; if (nvr == 0) return fmi3OK; NOT_SUPPORTED("fmi3SetClock") }

fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance c, fmi3ValueReference vr, size_t *n) {
    (void)vr; (void)n; NOT_SUPPORTED("fmi3GetNumberOfVariableDependencies") }
fmi3Status fmi3GetVariableDependencies(fmi3Instance c, fmi3ValueReference d, size_t e[],
        fmi3ValueReference i[], size_t ei[], fmi3DependencyKind k[], size_t n) {
    (void)d; (void)e; (void)i; (void)ei; (void)k; (void)n;
    NOT_SUPPORTED("fmi3GetVariableDependencies") }
fmi3Status fmi3GetFMUState(fmi3Instance c, fmi3FMUState *s) {
    Instance *inst = c;
    Model *copy = *s ? (Model *)*s : calloc(1, sizeof(Model));
    if (!copy) return fmi3Error;
    model_copy_state(copy, &inst->model);
    *s = copy;
    return fmi3OK;
}
fmi3Status fmi3SetFMUState(fmi3Instance c, fmi3FMUState s) {
    if (!s) return fmi3Error;
    model_copy_state(&((Instance *)c)->model, (const Model *)s);
    return fmi3OK;
}
fmi3Status fmi3FreeFMUState(fmi3Instance c, fmi3FMUState *s) {
    (void)c;
    if (s) { free(*s); *s = NULL; }
    return fmi3OK;
}
fmi3Status fmi3SerializedFMUStateSize(fmi3Instance c, fmi3FMUState s, size_t *n) {
    (void)c; (void)s; *n = model_serialized_size(); return fmi3OK;
}
fmi3Status fmi3SerializeFMUState(fmi3Instance c, fmi3FMUState s, fmi3Byte b[], size_t n) {
    if (!s || n < model_serialized_size()) {
        logmsg(c, fmi3Error, "fmi3SerializeFMUState: too few bytes");
        return fmi3Error;
    }
    model_serialize((const Model *)s, (char *)b);
    return fmi3OK;
}
fmi3Status fmi3DeserializeFMUState(fmi3Instance c, const fmi3Byte b[], size_t n, fmi3FMUState *s) {
    Model *copy = calloc(1, sizeof(Model));
    if (!copy) return fmi3Error;
    if (model_deserialize(copy, (const char *)b, n) != 0) {
        free(copy);
        logmsg(c, fmi3Error, "fmi3DeserializeFMUState: not a state of this FMU");
        return fmi3Error;
    }
    *s = copy;
    return fmi3OK;
}
static fmi3Status derivative(fmi3Instance c, const fmi3ValueReference z[], size_t nz,
        const fmi3ValueReference v[], size_t nv, const fmi3Float64 seed[], size_t ns,
        fmi3Float64 result[], size_t nr, int adjoint) {
    if (ns != (adjoint ? nz : nv) || nr != (adjoint ? nv : nz) ||
        model_directional(&((Instance *)c)->model, z, nz, v, nv, seed, result,
                          adjoint) != 0) {
        logmsg(c, fmi3Error, "directional derivatives: the unknowns must be "
               "derivatives or outputs, the knowns states, parameters or inputs");
        return fmi3Error;
    }
    return fmi3OK;
}
fmi3Status fmi3GetDirectionalDerivative(fmi3Instance c, const fmi3ValueReference u[], size_t nu,
        const fmi3ValueReference k[], size_t nk, const fmi3Float64 s[], size_t ns,
        fmi3Float64 r[], size_t nr) {
    return derivative(c, u, nu, k, nk, s, ns, r, nr, 0);
}
fmi3Status fmi3GetAdjointDerivative(fmi3Instance c, const fmi3ValueReference u[], size_t nu,
        const fmi3ValueReference k[], size_t nk, const fmi3Float64 s[], size_t ns,
        fmi3Float64 r[], size_t nr) {
    return derivative(c, u, nu, k, nk, s, ns, r, nr, 1);
}
fmi3Status fmi3EnterConfigurationMode(fmi3Instance c) { NOT_SUPPORTED("fmi3EnterConfigurationMode") }
fmi3Status fmi3ExitConfigurationMode(fmi3Instance c) { NOT_SUPPORTED("fmi3ExitConfigurationMode") }
fmi3Status fmi3GetIntervalDecimal(fmi3Instance c, const fmi3ValueReference vr[], size_t n,
        fmi3Float64 v[], fmi3IntervalQualifier q[]) {
    (void)vr; (void)n; (void)v; (void)q; NOT_SUPPORTED("fmi3GetIntervalDecimal") }
fmi3Status fmi3GetIntervalFraction(fmi3Instance c, const fmi3ValueReference vr[], size_t n,
        fmi3UInt64 a[], fmi3UInt64 b[], fmi3IntervalQualifier q[]) {
    (void)vr; (void)n; (void)a; (void)b; (void)q; NOT_SUPPORTED("fmi3GetIntervalFraction") }
fmi3Status fmi3GetShiftDecimal(fmi3Instance c, const fmi3ValueReference vr[], size_t n, fmi3Float64 v[]) {
    (void)vr; (void)n; (void)v; NOT_SUPPORTED("fmi3GetShiftDecimal") }
fmi3Status fmi3GetShiftFraction(fmi3Instance c, const fmi3ValueReference vr[], size_t n,
        fmi3UInt64 a[], fmi3UInt64 b[]) {
    (void)vr; (void)n; (void)a; (void)b; NOT_SUPPORTED("fmi3GetShiftFraction") }
fmi3Status fmi3SetIntervalDecimal(fmi3Instance c, const fmi3ValueReference vr[], size_t n, const fmi3Float64 v[]) {
    (void)vr; (void)n; (void)v; NOT_SUPPORTED("fmi3SetIntervalDecimal") }
fmi3Status fmi3SetIntervalFraction(fmi3Instance c, const fmi3ValueReference vr[], size_t n,
        const fmi3UInt64 a[], const fmi3UInt64 b[]) {
    (void)vr; (void)n; (void)a; (void)b; NOT_SUPPORTED("fmi3SetIntervalFraction") }
fmi3Status fmi3SetShiftDecimal(fmi3Instance c, const fmi3ValueReference vr[], size_t n, const fmi3Float64 v[]) {
    (void)vr; (void)n; (void)v; NOT_SUPPORTED("fmi3SetShiftDecimal") }
fmi3Status fmi3SetShiftFraction(fmi3Instance c, const fmi3ValueReference vr[], size_t n,
        const fmi3UInt64 a[], const fmi3UInt64 b[]) {
    (void)vr; (void)n; (void)a; (void)b; NOT_SUPPORTED("fmi3SetShiftFraction") }
fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance c) { (void)c; return fmi3OK; }

fmi3Status fmi3UpdateDiscreteStates(fmi3Instance c, fmi3Boolean *update,
        fmi3Boolean *terminate, fmi3Boolean *nominals, fmi3Boolean *values,
        fmi3Boolean *timeDefined, fmi3Float64 *nextTime) {
    Instance *inst = c;
    int again = 0, changed = model_event(&inst->model, &again);
    *update = again ? fmi3True : fmi3False; *terminate = fmi3False;
    *nominals = fmi3False; *values = changed ? fmi3True : fmi3False;
    *timeDefined = fmi3False; *nextTime = 0;
    return fmi3OK;
}

/* Model Exchange */
fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance c) { (void)c; return fmi3OK; }

fmi3Status fmi3CompletedIntegratorStep(fmi3Instance c, fmi3Boolean noSet,
        fmi3Boolean *enterEventMode, fmi3Boolean *terminate) {
    (void)c; (void)noSet;
    *enterEventMode = fmi3False; *terminate = fmi3False;
    return fmi3OK;
}

fmi3Status fmi3SetTime(fmi3Instance c, fmi3Float64 time) {
    Instance *inst = c;
    inst->model.time = time;
    inst->model.stale = 1;
    return fmi3OK;
}

fmi3Status fmi3SetContinuousStates(fmi3Instance c, const fmi3Float64 x[], size_t nx) {
    Instance *inst = c;
    if (nx != MODEL_NX) return fmi3Error;
    memcpy(inst->model.x, x, sizeof(double) * nx);
    inst->model.stale = 1;
    return fmi3OK;
}

fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance c, fmi3Float64 dx[], size_t nx) {
    Instance *inst = c;
    if (nx != MODEL_NX) return fmi3Error;
    model_evaluate(&inst->model);
    memcpy(dx, inst->model.xdot, sizeof(double) * nx);
    if (model_finite(&inst->model) != 0) {
        logmsg(inst, fmi3Error, "der(%s) is not finite at t = %g (check the "
               "parameters)", model_state_name(model_finite(&inst->model) - 1),
               inst->model.time);
        return fmi3Error;
    }
    return fmi3OK;
}

fmi3Status fmi3GetEventIndicators(fmi3Instance c, fmi3Float64 z[], size_t nz) {
    if (nz != MODEL_NR) return fmi3Error;
    if (nz) model_indicators(&((Instance *)c)->model, z);
    return fmi3OK;
}

fmi3Status fmi3GetContinuousStates(fmi3Instance c, fmi3Float64 x[], size_t nx) {
    Instance *inst = c;
    if (nx != MODEL_NX) return fmi3Error;
    memcpy(x, inst->model.x, sizeof(double) * nx);
    return fmi3OK;
}

fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance c, fmi3Float64 x[], size_t nx) {
    size_t i;
    (void)c;
    for (i = 0; i < nx; i++) x[i] = 1.0;
    return fmi3OK;
}

fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance c, size_t *n) {
    (void)c; *n = MODEL_NR; return fmi3OK;
}

fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance c, size_t *n) {
    (void)c; *n = MODEL_NX; return fmi3OK;
}

/* Co-Simulation and Scheduled Execution (not provided by this FMU) */
fmi3Status fmi3EnterStepMode(fmi3Instance c) { (void)c; return fmi3OK; }
fmi3Status fmi3GetOutputDerivatives(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,
        const fmi3Int32 o[], fmi3Float64 v[], size_t n) {
    (void)vr; (void)o; (void)v; (void)n; if (nvr == 0) return fmi3OK;
    NOT_SUPPORTED("fmi3GetOutputDerivatives") }
fmi3Status fmi3DoStep(fmi3Instance c, fmi3Float64 t, fmi3Float64 h, fmi3Boolean noSet,
        fmi3Boolean *event, fmi3Boolean *terminate, fmi3Boolean *early, fmi3Float64 *last) {
    Instance *inst = c;
    (void)noSet;
    *event = fmi3False; *terminate = fmi3False; *early = fmi3False;
    if (h < 0) return fmi3Error;
    inst->model.time = t;
    switch (model_integrate(&inst->model, t + h)) {
    case 0: break;
    case 2:
        logmsg(inst, fmi3Error, "the derivatives are not finite in the step "
               "from t = %g (check the parameters)", inst->model.time);
        *last = inst->model.time;
        return fmi3Error;
    default:
        logmsg(inst, fmi3Error, "the integrator failed at t = %g (step size too small)",
               inst->model.time);
        *last = inst->model.time;
        return fmi3Error;
    }
    *last = inst->model.time;
    return fmi3OK;
}
fmi3Status fmi3ActivateModelPartition(fmi3Instance c, fmi3ValueReference clock, fmi3Float64 t) {
    (void)clock; (void)t; NOT_SUPPORTED("fmi3ActivateModelPartition") }
