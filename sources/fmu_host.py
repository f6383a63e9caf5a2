"""The calls into a third-party FMU's binary, in a child process.

A binary that crashes (a segfault on load or in
``fmi2GetDirectionalDerivative``), hangs or returns NaN must not take the
tool down nor pass as a result (FMI 2.0 and 3.0 Model Exchange alike).
:func:`sample_isolated` runs :func:`sample` in a child Python process
(``python -m sources.fmu_host``, the jobs pickled on its stdin, the
results on its stdout); the child says which FMI call it is in (a line on its stderr)
before each one, so that a crash, a hang past :func:`timeout_s` or a
non-finite value becomes one :class:`~sources.fmus.FmuError`
naming the FMU and the call. The parent unpacks the FMU once per content
(:func:`fmu.store.unpacked`, the user's cache); the child only reads
that folder.

The child imports numpy and fmpy only (about 0.2 s), runs in its own
session (a terminal's Ctrl-C reaches the parent, which kills it) and
dies with its parent.
"""

import ctypes
import pickle
import sys
from ctypes import byref
from dataclasses import dataclass

import numpy as np

from infra.environment import positive_setting
from infra.children import (die_with_parent, run_child, signal_name,
                             write_stage)

__all__ = ["SampleJob", "sample", "sample_isolated", "timeout_s",
           "TIMEOUT_S"]

#: Seconds the FMU's calls may take in all before they count as hung
#: (a small FMU takes milliseconds); ``JUDDER_FMU_TIMEOUT`` sets another.
TIMEOUT_S = 120.0
#: Prefix of the child's lines that name the call it is in.
_STAGE = "judder-fmu-call: "


def _stage(text):
    """In the child: name the step it starts (:data:`_STAGE`)."""
    write_stage(_STAGE, text)


class FmuCallError(Exception):
    """An FMI call returned an error (raised in the child, reported by
    the parent as an ``FmuError``)."""


@dataclass(frozen=True)
class SampleJob:
    """What the child needs: the FMU's identity, parameter values and the
    points at which the Jacobian is read.

    Attributes
    ----------
    path : str
        The FMU file (for messages).
    folder : str
        Where it is extracted.
    guid, model_identifier : str
    fmi_version : str
        ``"2.0"`` or ``"3.0"``.
    directional : bool
        The FMU provides directional derivatives (else the Jacobian is
        read by central differences).
    states, derivatives : tuple of int
        Value references of ``x`` and ``der(x)``.
    references : dict of str to int
        Value references of the Real parameters.
    values : dict of str to float
        Parameters (SI), without the amplitude.
    amplitude : str
        Name of the dither amplitude parameter.
    amplitudes : tuple of float
        Its values (Pa), one instance each.
    times : tuple of float
        Times (s) at which the Jacobian is read.
    """

    path: str
    folder: str
    guid: str
    model_identifier: str
    fmi_version: str
    directional: bool
    states: tuple
    derivatives: tuple
    references: dict
    values: dict
    amplitude: str
    amplitudes: tuple
    times: tuple


def timeout_s():
    """The hang limit: ``JUDDER_FMU_TIMEOUT`` (seconds) or
    :data:`TIMEOUT_S`."""
    return positive_setting("JUDDER_FMU_TIMEOUT", TIMEOUT_S, "seconds")


#: Relative step of the central differences that read the Jacobian of an
#: FMU without directional derivatives: about the cube root of the
#: machine epsilon, where truncation and round-off balance.
DIFFERENCE_STEP = 6e-6


class _Instance:
    """One initialised Model Exchange instance at a parameter set (FMI 2.0
    or 3.0); the FMU's log messages are kept (the last one explains a
    failed call)."""

    def __init__(self, job, values):
        self.job = job
        self.n = len(job.states)
        self.messages = []
        self.fmu = None
        self.prefix = "fmi3" if job.fmi_version == "3.0" else "fmi2"
        names = list(values)
        self._call("loading the binary", lambda: setattr(
            self, "fmu", self._load()))
        fmu = self.fmu
        if self.prefix == "fmi2":
            self._call("fmi2Instantiate", lambda: fmu.instantiate(
                callbacks=self.callbacks))
            self._call("fmi2SetupExperiment",
                       lambda: fmu.setupExperiment(startTime=0.0))
            self._call("fmi2SetReal", lambda: fmu.setReal(
                [job.references[n] for n in names],
                [values[n] for n in names]))
            self._call("fmi2EnterInitializationMode",
                       fmu.enterInitializationMode)
        else:
            self._call("fmi3InstantiateModelExchange",
                       lambda: fmu.instantiate(logMessage=self.callback))
            self._call("fmi3SetFloat64", lambda: fmu.setFloat64(
                [job.references[n] for n in names],
                [values[n] for n in names]))
            self._call("fmi3EnterInitializationMode",
                       lambda: fmu.enterInitializationMode(startTime=0.0))
        self._call(f"{self.prefix}ExitInitializationMode",
                   fmu.exitInitializationMode)
        new_states = fmu.newDiscreteStates if self.prefix == "fmi2" \
            else fmu.updateDiscreteStates
        while True:
            update = self._call(
                "fmi2NewDiscreteStates" if self.prefix == "fmi2"
                else "fmi3UpdateDiscreteStates", new_states)
            if not update[0] or update[1]:
                break
        self._call(f"{self.prefix}EnterContinuousTimeMode",
                   fmu.enterContinuousTimeMode)
        buffer = (ctypes.c_double * self.n)()
        self._call(f"{self.prefix}GetContinuousStates",
                   lambda: fmu.getContinuousStates(buffer, self.n))
        self.x0 = np.array(buffer)

    def _load(self):
        """The FMU's binary, loaded, with the logger kept alive."""
        job = self.job
        if self.prefix == "fmi2":
            from fmpy import calloc, free
            from fmpy.fmi2 import (FMU2Model,
                                   fmi2CallbackAllocateMemoryTYPE,
                                   fmi2CallbackFreeMemoryTYPE,
                                   fmi2CallbackFunctions,
                                   fmi2CallbackLoggerTYPE)
            from fmpy.logging import addLoggerProxy
            self.callbacks = fmi2CallbackFunctions()
            self.callbacks.logger = fmi2CallbackLoggerTYPE(
                lambda component, instance, status, category, message:
                self._log(message))
            self.callbacks.allocateMemory = \
                fmi2CallbackAllocateMemoryTYPE(calloc)
            self.callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
            addLoggerProxy(byref(self.callbacks))
            model = FMU2Model
        else:
            from fmpy.fmi3 import FMU3Model
            self.callback = (lambda environment, status, category, message:
                             self._log(message))
            model = FMU3Model
        return model(guid=job.guid, unzipDirectory=job.folder,
                     modelIdentifier=job.model_identifier,
                     instanceName="judder")

    def _log(self, message):
        self.messages.append(message.decode("utf-8", "replace")
                             if isinstance(message, bytes) else str(message))

    def _call(self, name, call):
        _stage(name)
        try:
            return call()
        except Exception as exc:       # fmpy's FMICallException, OSError
            reason = self.messages[-1] if self.messages else str(exc)
            raise FmuCallError(f"{name} failed ({reason})") from None

    def _rate(self, x, at):
        """``der(x)`` at the instance's time and the states ``x``."""
        fmu, n = self.fmu, self.n
        rate = (ctypes.c_double * n)()
        self._call(f"{self.prefix}SetContinuousStates" + at,
                   lambda: fmu.setContinuousStates(
                       (ctypes.c_double * n)(*x), n))
        get = fmu.getDerivatives if self.prefix == "fmi2" \
            else fmu.getContinuousStateDerivatives
        self._call(("fmi2GetDerivatives" if self.prefix == "fmi2"
                    else "fmi3GetContinuousStateDerivatives") + at,
                   lambda: get(rate, n))
        return np.array(rate)

    def jacobian(self, time, x):
        """``d der(x) / dx`` at ``(time, x)`` and ``der(x)``: by
        directional derivatives where the FMU provides them, else by
        central differences (steps :data:`DIFFERENCE_STEP` relative)."""
        fmu = self.fmu
        at = f" at t = {time:g} s"
        self._call(f"{self.prefix}SetTime" + at, lambda: fmu.setTime(time))
        if not self.job.directional:
            columns = []
            for i in range(self.n):
                step = DIFFERENCE_STEP * max(1.0, abs(x[i]))
                up, down = np.array(x, float), np.array(x, float)
                up[i] += step
                down[i] -= step
                columns.append((self._rate(up, at) - self._rate(down, at))
                               / (2 * step))
            return np.array(columns).T, self._rate(x, at)
        rate = self._rate(x, at)
        columns = [self._call(
            f"{self.prefix}GetDirectionalDerivative" + at,
            lambda seed=seed: fmu.getDirectionalDerivative(
                list(self.job.derivatives), list(self.job.states),
                list(seed)))
            for seed in np.eye(self.n)]
        return np.array(columns).T, rate

    def close(self):
        """Free the instance and unload the binary."""
        if self.fmu is None:
            return
        for name, call in ((f"{self.prefix}Terminate", self.fmu.terminate),
                           (f"{self.prefix}FreeInstance",
                            self.fmu.freeInstance)):
            _stage(name)
            try:
                call()
            except Exception:      # noqa: BLE001 - whatever state it is in
                pass
        _stage("unloading the binary")
        self.fmu.freeLibrary()


def sample(job):
    """The Jacobians of every amplitude at every time, read in this
    process.

    Returns
    -------
    dict
        ``jacobians``: array (amplitudes, times, n, n), 1/s (SI per SI);
        ``x0``, ``rate``: the first instance's initial state and its
        derivative, shape (n,); ``moved``, ``along``: its Jacobian at
        ``x0`` plus a generic move of every state and plus the last time
        along ``rate`` (for the steady-slip check), shape (n, n).
    """
    out, first = [], {}
    for k, a in enumerate(job.amplitudes):
        instance = _Instance(job, {**job.values, job.amplitude: a})
        try:
            x0 = instance.x0
            if k == 0:
                A0, rate = instance.jacobian(0.0, x0)
                generic = 1e-2 * (1.0 + np.abs(x0)) * np.linspace(
                    1.0, 2.0, len(x0))
                first = {"x0": x0, "rate": rate,
                         "moved": instance.jacobian(0.0, x0 + generic)[0],
                         "along": instance.jacobian(
                             0.0, x0 + job.times[-1] * rate)[0]}
            out.append([instance.jacobian(t, first["x0"])[0]
                        for t in job.times])
        finally:
            instance.close()
    return {"jacobians": np.array(out), **first}


def sample_isolated(jobs, fmu_error):
    """:func:`sample` of each of ``jobs`` in one child process.

    Parameters
    ----------
    jobs : sequence of SampleJob
        Of one FMU (its ``path``); their ``folder`` is ignored: the FMU's
        folder is :func:`fmu.store.unpacked`. A child takes about 0.2 s,
        far more than the Jacobians of a small FMU: a linearisation asks
        for all its samples at once.
    fmu_error : type
        The exception raised for an FMU that crashed, hung, failed a call
        or returned a non-finite value (its message names the FMU and
        the call).

    Returns
    -------
    list of dict
        As :func:`sample`, one per job, every array finite.
    """
    from fmu.store import FmuFileError, unpacked
    path = jobs[0].path
    limit = timeout_s()
    try:
        folder = unpacked(path)
    except FmuFileError as exc:
        raise fmu_error(f"`path` {exc}") from None
    jobs = [SampleJob(**{**job.__dict__, "folder": folder}) for job in jobs]
    reply, stages, status, _ = run_child(
        ("-m", "sources.fmu_host"), jobs, limit, _STAGE)
    where = stages[-1] if stages else "starting"
    if status is None:
        raise fmu_error(f"`path` {path}: no answer within {limit:g} s "
                        f"(in {where}); allowed: an FMU whose calls "
                        "return (JUDDER_FMU_TIMEOUT=SECONDS allows more "
                        "time)")
    if status < 0:
        raise fmu_error(f"`path` {path}: the FMU's binary crashed "
                        f"({signal_name(status)}) in {where}; judder ran "
                        "it in a child process: nothing else is affected, "
                        "but this FMU cannot be used")
    if reply is None:
        raise RuntimeError(f"the FMU's child process ended with status "
                           f"{status} in {where} without a result")
    kind, value = reply
    if kind == "error":
        raise fmu_error(f"`path` {path}: {value}")
    for job, sampled in zip(jobs, value):
        _check_finite(job, sampled, fmu_error)
    return value


def _check_finite(job, value, fmu_error):
    for name, call in (("x0", "fmi2GetContinuousStates"),
                       ("rate", "fmi2GetDerivatives")):
        if not np.isfinite(value[name]).all():
            raise fmu_error(f"`path` {job.path}: {call} returned a "
                            "non-finite value (NaN or inf) at t = 0 s; "
                            "allowed: finite states and derivatives")
    for name in ("moved", "along"):
        if not np.isfinite(value[name]).all():
            raise fmu_error(f"`path` {job.path}: the FMU's Jacobian"
                            " has a non-finite value (NaN or inf) at "
                            "t = 0 s near the start values; allowed: a "
                            "finite Jacobian")
    bad = np.argwhere(~np.isfinite(value["jacobians"]).all(axis=(2, 3)))
    if len(bad):
        k, i = bad[0]
        raise fmu_error(
            f"`path` {job.path}: the FMU's Jacobian has a "
            f"non-finite value (NaN or inf) at t = {job.times[i]:g} s, "
            f"{job.amplitude} = {job.amplitudes[k]:g} Pa; allowed: a "
            "finite Jacobian")


def _child():
    die_with_parent()
    jobs = pickle.load(sys.stdin.buffer)
    try:
        reply = ("ok", [sample(job) for job in jobs])
    except FmuCallError as exc:
        reply = ("error", str(exc))
    sys.stdout.buffer.write(pickle.dumps(reply))
    sys.stdout.flush()


if __name__ == "__main__":
    _child()
