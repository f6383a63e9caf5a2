/* FMI 3.0 Model Exchange and Co-Simulation: an adapter of the calls
 * common to FMI 2 and 3 (instance.c) to the FMI 3.0 API.
 * Only Float64 variables exist; the other types and clocks report an
 * error. */
#include <stdlib.h>
#include <string.h>
#include "fmi3Functions.h"
#include "instance.h"

typedef struct {
    Instance core;             /* first: an Fmi3 is an Instance */
    fmi3InstanceEnvironment environment;
    fmi3LogMessageCallback log;
    int cosimulation;
} Fmi3;

#define CORE(c) ((Instance *)(c))
#define STATUS(failed) ((failed) ? fmi3Error : fmi3OK)

static void fmi3_log(Instance *core, int error, const char *text) {
    Fmi3 *c = (Fmi3 *)core;
    if (!c->log) return;
    c->log(c->environment,
           error == 1 ? fmi3Error : error ? fmi3Warning : fmi3OK,
           error == 1 ? "logStatusError" : error ? "logStatusWarning" :
           "logAll", text);
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
    Fmi3 *c;
    if (!token || strcmp(token, MODEL_GUID) != 0) {
        if (log) log(environment, fmi3Error, "logStatusError",
                     "wrong instantiation token");
        return NULL;
    }
    c = calloc(1, sizeof(Fmi3));
    if (!c) return NULL;
    c->environment = environment;
    c->log = log;
    c->cosimulation = cosimulation;
    if (instance_init(&c->core, name, fmi3_log) != 0) {
        free(c);
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
    if (!c) return;
    instance_free(CORE(c));
    free(c);
}

fmi3Status fmi3EnterInitializationMode(fmi3Instance c, fmi3Boolean toleranceDefined,
        fmi3Float64 tolerance, fmi3Float64 startTime,
        fmi3Boolean stopTimeDefined, fmi3Float64 stopTime) {
    (void)stopTimeDefined; (void)stopTime;
    instance_setup(CORE(c), ((Fmi3 *)c)->cosimulation && toleranceDefined,
                   tolerance, startTime);
    /* values with initial() true until the mode is left */
    instance_initialize(CORE(c));
    return fmi3OK;
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance c) {
    /* states and discrete variables follow the parameters set */
    return STATUS(instance_start(CORE(c)));
}

fmi3Status fmi3EnterEventMode(fmi3Instance c) { (void)c; return fmi3OK; }
fmi3Status fmi3Terminate(fmi3Instance c) { (void)c; return fmi3OK; }

fmi3Status fmi3Reset(fmi3Instance c) {
    return instance_reset(CORE(c)) ? fmi3Fatal : fmi3OK;
}

fmi3Status fmi3GetFloat64(fmi3Instance c, const fmi3ValueReference vr[],
                          size_t nvr, fmi3Float64 value[], size_t n) {
    if (n != nvr) return fmi3Error;
    return STATUS(instance_get(CORE(c), vr, nvr, value, "Float64"));
}

fmi3Status fmi3SetFloat64(fmi3Instance c, const fmi3ValueReference vr[],
                          size_t nvr, const fmi3Float64 value[], size_t n) {
    if (n != nvr) return fmi3Error;
    return STATUS(instance_set(CORE(c), vr, nvr, value));
}

#define NO_VARIABLES(name, type) \
    fmi3Status name(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr, type value[], size_t n) { \
        (void)vr; (void)value; (void)n; \
        return STATUS(instance_no_variables(CORE(c), #name, nvr)); }
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

#define NOT_SUPPORTED(call) { return STATUS(instance_not_supported(CORE(c), call)); }

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
    return STATUS(instance_get_state(CORE(c), s));
}
fmi3Status fmi3SetFMUState(fmi3Instance c, fmi3FMUState s) {
    return STATUS(instance_set_state(CORE(c), s));
}
fmi3Status fmi3FreeFMUState(fmi3Instance c, fmi3FMUState *s) {
    (void)c; instance_free_state(s); return fmi3OK;
}
fmi3Status fmi3SerializedFMUStateSize(fmi3Instance c, fmi3FMUState s, size_t *n) {
    (void)c; (void)s; *n = model_serialized_size(); return fmi3OK;
}
fmi3Status fmi3SerializeFMUState(fmi3Instance c, fmi3FMUState s, fmi3Byte b[], size_t n) {
    return STATUS(instance_serialize(CORE(c), s, (char *)b, n, "fmi3SerializeFMUState"));
}
fmi3Status fmi3DeserializeFMUState(fmi3Instance c, const fmi3Byte b[], size_t n, fmi3FMUState *s) {
    return STATUS(instance_deserialize(CORE(c), (const char *)b, n, s,
                                       "fmi3DeserializeFMUState"));
}
static fmi3Status derivative(fmi3Instance c, const fmi3ValueReference z[], size_t nz,
        const fmi3ValueReference v[], size_t nv, const fmi3Float64 seed[], size_t ns,
        fmi3Float64 result[], size_t nr, int adjoint) {
    if (ns != (adjoint ? nz : nv) || nr != (adjoint ? nv : nz))
        return STATUS(instance_not_supported(CORE(c), "directional derivatives "
                      "with seed and result sizes other than the unknowns' and knowns'"));
    return STATUS(instance_directional(CORE(c), z, nz, v, nv, seed, result, adjoint));
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
    int again, changed;
    int failed = instance_event(CORE(c), &again, &changed);
    *update = again ? fmi3True : fmi3False; *terminate = fmi3False;
    *nominals = fmi3False; *values = changed ? fmi3True : fmi3False;
    *timeDefined = fmi3False; *nextTime = 0;
    return STATUS(failed);
}

/* Model Exchange */
fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance c) { (void)c; return fmi3OK; }

fmi3Status fmi3CompletedIntegratorStep(fmi3Instance c, fmi3Boolean noSet,
        fmi3Boolean *enterEventMode, fmi3Boolean *terminate) {
    (void)noSet;
    *enterEventMode = fmi3False; *terminate = fmi3False;
    return STATUS(instance_check(CORE(c)));   /* the model's asserts */
}

fmi3Status fmi3SetTime(fmi3Instance c, fmi3Float64 time) {
    instance_set_time(CORE(c), time);
    return fmi3OK;
}

fmi3Status fmi3SetContinuousStates(fmi3Instance c, const fmi3Float64 x[], size_t nx) {
    return STATUS(instance_set_states(CORE(c), x, nx));
}

fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance c, fmi3Float64 dx[], size_t nx) {
    return STATUS(instance_derivatives(CORE(c), dx, nx));
}

fmi3Status fmi3GetEventIndicators(fmi3Instance c, fmi3Float64 z[], size_t nz) {
    return STATUS(instance_indicators(CORE(c), z, nz));
}

fmi3Status fmi3GetContinuousStates(fmi3Instance c, fmi3Float64 x[], size_t nx) {
    return STATUS(instance_get_states(CORE(c), x, nx));
}

fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance c, fmi3Float64 x[], size_t nx) {
    (void)c; instance_nominals(x, nx); return fmi3OK;
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
    int failed;
    (void)noSet;
    *event = fmi3False; *terminate = fmi3False; *early = fmi3False;
    failed = instance_do_step(CORE(c), t, h);
    *last = CORE(c)->model.time;
    return STATUS(failed);
}
fmi3Status fmi3ActivateModelPartition(fmi3Instance c, fmi3ValueReference clock, fmi3Float64 t) {
    (void)clock; (void)t; NOT_SUPPORTED("fmi3ActivateModelPartition") }
