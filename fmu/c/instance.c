/* The FMI calls common to FMI 2.0 and 3.0 (see instance.h). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "instance.h"

void instance_log(Instance *c, int error, const char *format, ...) {
    char text[512];
    va_list args;
    if (!c || !c->log) return;
    va_start(args, format);
    vsnprintf(text, sizeof(text), format, args);
    va_end(args);
    c->log(c, error, text);
}

int instance_init(Instance *c, const char *name, InstanceLogger log) {
    c->log = log;
    c->name = malloc(strlen(name ? name : "") + 1);
    if (!c->name) return 1;
    strcpy(c->name, name ? name : "");
    if (model_init(&c->model) != 0) {
        free(c->name);
        c->name = NULL;
        return 1;
    }
    return 0;
}

void instance_free(Instance *c) {
    model_free(&c->model);
    free(c->name);
}

int instance_reset(Instance *c) {
    model_free(&c->model);
    return model_init(&c->model) != 0;
}

void instance_setup(Instance *c, int tolerance_defined, double tolerance,
                    double start_time) {
    if (tolerance_defined && tolerance > 0)
        c->model.relative_tolerance = tolerance < 1e-3 ? tolerance : 1e-3;
    instance_set_time(c, start_time);
}

void instance_set_time(Instance *c, double time) {
    c->model.time = time;
    c->model.stale = 1;
}

int instance_get(Instance *c, const unsigned vr[], size_t n, double value[],
                 const char *kind) {
    size_t i;
    for (i = 0; i < n; i++) {
        if (model_get(&c->model, vr[i], &value[i]) != 0) {
            instance_log(c, 1, "no %s variable with value reference %u",
                         kind, vr[i]);
            return 1;
        }
    }
    return 0;
}

int instance_set(Instance *c, const unsigned vr[], size_t n,
                 const double value[]) {
    size_t i;
    for (i = 0; i < n; i++) {
        int done = model_set(&c->model, vr[i], value[i], 0);
        if (done == 2) {
            double low, high;
            model_bounds(vr[i], &low, &high);
            instance_log(c, 1, "value %g of value reference %u is outside "
                         "its declared range [%g, %g]", value[i], vr[i], low,
                         high);
            return 1;
        }
        if (done != 0) {
            instance_log(c, 1, "value reference %u cannot be set", vr[i]);
            return 1;
        }
    }
    return 0;
}

int instance_no_variables(Instance *c, const char *call, size_t n) {
    if (n == 0) return 0;
    instance_log(c, 1, "%s: the model has no variables of this type", call);
    return 1;
}

int instance_not_supported(Instance *c, const char *call) {
    instance_log(c, 1, "%s is not supported", call);
    return 1;
}

int instance_get_state(Instance *c, void **state) {
    Model *copy = *state ? (Model *)*state : calloc(1, sizeof(Model));
    if (!copy) return 1;
    model_copy_state(copy, &c->model);
    *state = copy;
    return 0;
}

int instance_set_state(Instance *c, const void *state) {
    if (!state) return 1;
    model_copy_state(&c->model, (const Model *)state);
    return 0;
}

void instance_free_state(void **state) {
    if (state) {
        free(*state);
        *state = NULL;
    }
}

int instance_serialize(Instance *c, const void *state, char *bytes,
                       size_t size, const char *call) {
    if (!state || size < model_serialized_size()) {
        instance_log(c, 1, "%s: %zu bytes given, %zu needed", call, size,
                     model_serialized_size());
        return 1;
    }
    model_serialize((const Model *)state, bytes);
    return 0;
}

int instance_deserialize(Instance *c, const char *bytes, size_t size,
                         void **state, const char *call) {
    Model *copy = calloc(1, sizeof(Model));
    if (!copy) return 1;
    if (model_deserialize(copy, bytes, size) != 0) {
        free(copy);
        instance_log(c, 1, "%s: not a state of this FMU", call);
        return 1;
    }
    *state = copy;
    return 0;
}

int instance_directional(Instance *c, const unsigned z[], size_t nz,
                         const unsigned v[], size_t nv, const double seed[],
                         double result[], int adjoint) {
    if (model_directional(&c->model, z, nz, v, nv, seed, result,
                          adjoint) != 0) {
        instance_log(c, 1, "directional derivatives: the unknowns must be "
                     "derivatives or outputs, the knowns states, parameters "
                     "or inputs");
        return 1;
    }
    return 0;
}

static void log_iterations(Instance *c) {
    instance_log(c, 1, "the event iteration at t = %g did not converge in "
                 "%d iterations (the discrete variables or relations keep "
                 "changing)", c->model.time, MODEL_MAX_EVENT_ITERATIONS);
}

static void log_chattering(Instance *c) {
    instance_log(c, 1, "the model chatters at t = %.9g: more than %d "
                 "events within %g s (a relation switches back as soon as "
                 "it has switched, a Zeno model); allowed: a model whose "
                 "events are apart (a hysteresis or a stuck mode)",
                 c->model.time, MODEL_ZENO_EVENTS,
                 MODEL_ZENO_SPAN * (fabs(c->model.time) + 1.0));
}

int instance_check(Instance *c) {
    char text[400];
    int error = 0;
    while (model_assertion(&c->model, text, sizeof(text), &error)) {
        instance_log(c, error ? 1 : 2, "assert %s at t = %.9g: %s",
                     error ? "failed" : "warning", c->model.time, text);
        if (error) return 1;
    }
    return 0;
}

void instance_initialize(Instance *c) {
    model_initialize(&c->model);
}

int instance_start(Instance *c) {
    if (model_start(&c->model) == 0) return instance_check(c);
    log_iterations(c);
    return 1;
}

int instance_event(Instance *c, int *again, int *states_changed) {
    *again = 0;
    *states_changed = model_event(&c->model, again);
    if (model_chattering(&c->model)) {
        log_chattering(c);
        return 1;
    }
    if (c->model.iterations < MODEL_MAX_EVENT_ITERATIONS)
        return *again ? 0 : instance_check(c);
    log_iterations(c);
    return 1;
}

int instance_set_states(Instance *c, const double x[], size_t nx) {
    if (nx != MODEL_NX) return 1;
    memcpy(c->model.x, x, sizeof(double) * nx);
    c->model.stale = 1;
    return 0;
}

int instance_get_states(Instance *c, double x[], size_t nx) {
    if (nx != MODEL_NX) return 1;
    memcpy(x, c->model.x, sizeof(double) * nx);
    return 0;
}

int instance_derivatives(Instance *c, double dx[], size_t nx) {
    int bad;
    if (nx != MODEL_NX) return 1;
    model_evaluate(&c->model);
    memcpy(dx, c->model.xdot, sizeof(double) * nx);
    bad = model_finite(&c->model);
    if (bad != 0) {
        instance_log(c, 1, "der(%s) is not finite at t = %g (check the "
                     "parameters)", model_state_name(bad - 1), c->model.time);
        return 1;
    }
    return 0;
}

int instance_indicators(Instance *c, double z[], size_t nz) {
    if (nz != MODEL_NR) return 1;
    if (nz) model_indicators(&c->model, z);
    return 0;
}

void instance_nominals(double x[], size_t nx) {
    size_t i;
    for (i = 0; i < nx; i++) x[i] = 1.0;
}

int instance_do_step(Instance *c, double t, double h) {
    if (h < 0) return 1;
    c->model.time = t;
    switch (model_integrate(&c->model, t + h)) {
    case 0:
        return instance_check(c);   /* warnings at communication points */
    case 5:
        return instance_check(c);   /* the failed assert, with its time */
    case 2:
        instance_log(c, 1, "the derivatives are not finite in the step from "
                     "t = %g (check the parameters)", c->model.time);
        return 1;
    case 3:
        log_iterations(c);
        return 1;
    case 4:
        log_chattering(c);
        return 1;
    default:
        instance_log(c, 1, "the integrator failed at t = %g (step size too "
                     "small)", c->model.time);
        return 1;
    }
}
