/* A minimal FMI 2.0 Co-Simulation importer for Windows, used by the tests
 * under wine: loads binaries/win64/NAME.dll, runs it with fixed steps and
 * prints "time value" of one Real variable per line.
 *
 * usage: fmi2_host.exe DLL GUID STOP_TIME STEP VALUE_REFERENCE
 */
#include <stdio.h>
#include <stdlib.h>
#include <windows.h>
#include "fmi2FunctionTypes.h"

static void logger(fmi2ComponentEnvironment env, fmi2String name,
                   fmi2Status status, fmi2String category,
                   fmi2String message, ...) {
    (void)env; (void)name; (void)category;
    fprintf(stderr, "[%d] %s\n", (int)status, message);
}

#define LOAD(type, name) \
    type *name = (type *)GetProcAddress(library, #name); \
    if (!name) { fprintf(stderr, "no %s\n", #name); return 2; }

int main(int argc, char **argv) {
    HMODULE library;
    fmi2CallbackFunctions callbacks = {logger, calloc, free, NULL, NULL};
    fmi2Component c;
    fmi2ValueReference vr;
    double stop, step, t = 0, value;
    long k, n;
    if (argc != 6) { fprintf(stderr, "usage: DLL GUID STOP STEP VR\n"); return 2; }
    library = LoadLibraryA(argv[1]);
    if (!library) { fprintf(stderr, "cannot load %s\n", argv[1]); return 2; }
    stop = atof(argv[3]); step = atof(argv[4]); vr = (fmi2ValueReference)atoi(argv[5]);
    {
        LOAD(fmi2InstantiateTYPE, fmi2Instantiate)
        LOAD(fmi2SetupExperimentTYPE, fmi2SetupExperiment)
        LOAD(fmi2EnterInitializationModeTYPE, fmi2EnterInitializationMode)
        LOAD(fmi2ExitInitializationModeTYPE, fmi2ExitInitializationMode)
        LOAD(fmi2DoStepTYPE, fmi2DoStep)
        LOAD(fmi2GetRealTYPE, fmi2GetReal)
        LOAD(fmi2FreeInstanceTYPE, fmi2FreeInstance)
        c = fmi2Instantiate("host", fmi2CoSimulation, argv[2], "", &callbacks,
                            fmi2False, fmi2False);
        if (!c) return 3;
        if (fmi2SetupExperiment(c, fmi2False, 0, 0, fmi2True, stop) != fmi2OK ||
            fmi2EnterInitializationMode(c) != fmi2OK ||
            fmi2ExitInitializationMode(c) != fmi2OK) return 3;
        n = (long)(stop / step + 0.5);
        for (k = 0; k <= n; k++) {
            if (fmi2GetReal(c, &vr, 1, &value) != fmi2OK) return 3;
            printf("%.17g %.17g\n", t, value);
            if (k == n) break;
            if (fmi2DoStep(c, t, step, fmi2True) != fmi2OK) return 3;
            t = (k + 1) * step;
        }
        fmi2FreeInstance(c);
    }
    return 0;
}
