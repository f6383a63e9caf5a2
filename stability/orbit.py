r"""The periodic orbit of a dithered engagement, by harmonic balance.

What the bench sees as judder is the motion the engagement settles into:
the forced response of the driveline to the dither, made nonlinear by the
bounded friction curve, and, where that motion is unstable, what grows
out of it. This module computes that motion and its stability on the
equations the bench FMU runs (``Judder.Examples.TestBenchEngagement``):
the driveline of Eq. (1)-(2) about a steady slip :math:`w_s`, with the
clutch torque of ``Judder.Components.CurveWetClutch``,

.. math::
   M\ddot x + C\dot x + K x = -e\,\bigl(\tau(w_s + e^T\dot x, t)
   - \tau_s\bigr), \qquad
   \tau(w, t) = N_c R_m S \tanh\frac{w}{w_\varepsilon}
   \bigl(\mu(w)(m p_m + p_f\cos\omega t) + (1 - m)\mu_0 p_m\bigr),

:math:`\mu(w) = \mu_0 + \Delta\mu\tanh(\mu_g(|w| - w_{op})/\Delta\mu)`
(:mod:`stability.friction`), ``C`` the structural damping with the
bench's speed control (``c1 + d_control``) and :math:`\tau_s` the torque
of the steady slip, which the motor and the load balance. The mean slip
is held at :math:`w_s` (the frozen-slip view of an engagement, whose slip
changes slowly against the dither period): the mean torque the dither
rectifies, which would drift the slip on the bench, is reported
(:attr:`Orbit.drift_torque`), not balanced; :func:`drifted_orbit` follows
that drift quasi-statically over a bench run.

Only the slip speed enters the nonlinearity, so the balance condenses to
the harmonics of the slip-speed deviation :math:`u = e^T\dot x` (the
alternating frequency-time method):

.. math:: U_k + H(k\nu)\,F_k[\tau(w_s + u(t), t)] = 0, \qquad
          H(\Omega) = i\Omega\, e^T (K - \Omega^2 M + i\Omega C)^{-1} e,

for :math:`k = 1 \dots` with base frequency :math:`\nu = \omega`
(T-periodic orbits) or :math:`\omega/2` (2T, the double-period judder
that grows out of an orbit unstable through -1), solved by Newton's
method with the exact Jacobian. The orbit's own Floquet multipliers come
from the variational equation about it, whose slip damping is
:math:`\partial\tau/\partial w` along the orbit (for a small orbit, the
:math:`\mu_g N_c R_m S (m p_m + p_f\cos\omega t)` of Eq. 2-5: the
stability layer's view), with the rigid-body directions removed as
:mod:`stability.reduction` does. Its amplitude is the upstream speed's
(body ``e`` > 0, the clutch's engine-side disc), what the bench records.

A combination (quasi-periodic) judder is not a periodic orbit: where the
T-orbit loses stability through a complex pair, the orbit is reported
unstable and no settled amplitude is claimed.

References: Eq. (1)-(9) of the paper; the harmonic-balance and
pseudo-arclength continuation as in NLvib (Krack and Gross, *Harmonic
Balance for Nonlinear Vibration Problems*, Springer 2019, ch. 2-4).
"""

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg

from infra.errors import JudderError

from .friction import curve, curve_value
from .kinds import KINDS, classify

__all__ = ["EngagementModel", "Orbit", "OrbitBranch", "periodic_orbit",
           "drifted_orbit", "double_period_orbit", "continue_orbit",
           "DEFAULT_HARMONICS"]

#: Harmonics of the base frequency kept in the balance (T-orbits; twice
#: as many for 2T orbits).
DEFAULT_HARMONICS = 9
#: Newton stops when the residual is below this share of the slip-speed
#: amplitude scale (rad/s).
_TOLERANCE = 1e-10
_MAX_NEWTON = 40
#: Sub-steps of one period in the monodromy (fourth-order Magnus).
_MONODROMY_STEPS = 96


@dataclass(frozen=True)
class EngagementModel:
    """The bench engagement about a steady slip, as the orbit needs it.

    Attributes
    ----------
    mass, stiffness, damping : ndarray, shape (n, n)
        ``M`` (kg m^2), ``K`` (N m/rad) and the structural damping ``C``
        with the bench's additions (N m s/rad), without the clutch.
    clutch : ndarray, shape (n,)
        ``e``: ``e @ w`` is the slip speed.
    upstream : int
        Body whose speed the bench records (the clutch's engine side).
    clutch_factor : float
        ``N_c R_m S``, m^3.
    mu0, mu_g, delta_mu, w_op : float
        Friction curve (1, s/rad, 1, rad/s), :func:`stability.friction.
        curve_at`.
    slip : float
        Steady slip ``w_s``, rad/s.
    p_m : float
        Mean pressure, Pa.
    mean_pressure_damping : float
        ``m``: share of the mean load that follows the curve.
    w_small : float
        Slip over which the friction torque changes sign, rad/s.
    drive : int
        Body driven by a speed-controlled motor whose torque is limited
        (-1: none). Its proportional gain is in ``damping`` already; the
        limit is the nonlinearity :meth:`drive_excess`.
    drive_gain : float
        The controller's gain, N m s/rad.
    drive_limit : float
        Largest torque the motor delivers, N m (either sign).
    drive_torque : float
        The motor's torque at the steady slip, N m.
    drive_damping : float
        Damping to ground of the bodies the drive turns, its gain
        included, N m s/rad: their mean speed, which the clutch's
        upstream disc shares, settles where the motor's mean torque
        balances the clutch's and this damping's (the balance's mean
        unknown).
    load_inertia : float
        Inertia of the bodies the clutch's gearbox side turns, kg m^2
        (0: the slip held, the frozen-slip view).
    drift_time : float
        Time over which the mean slip drifts under the torque the dither
        rectifies before the motion is read, s (:func:`drifted_orbit`;
        0: none).
    table : drivelines.friction.FrictionTable or None
        The clutch's friction characteristic, read in place of the curve
        (``mu0`` is then its value at the steady slip, the friction of
        the mean load's share ``1 - m``; ``delta_mu`` and ``w_op`` are
        unused).
    """

    mass: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    clutch: np.ndarray
    upstream: int
    clutch_factor: float
    mu0: float
    mu_g: float
    delta_mu: float
    w_op: float
    slip: float
    p_m: float
    mean_pressure_damping: float = 0.0
    w_small: float = 0.01
    drive: int = -1
    drive_gain: float = 0.0
    drive_limit: float = np.inf
    drive_torque: float = 0.0
    drive_damping: float = 0.0
    load_inertia: float = 0.0
    drift_time: float = 0.0
    table: object = None

    @classmethod
    def from_driveline(cls, driveline, delta_mu, w_op, slip=None,
                       w_small=0.01, table=None):
        """The engagement of a :class:`stability.model.Driveline` whose
        ``mu0`` and ``mu_g`` are the curve's at ``w_op``, with its
        structural damping as the linear part (the bench's additions
        already in its parameters), at the slip ``slip`` (default
        ``w_op``), without a limited drive (set its ``drive_*`` fields
        with :func:`dataclasses.replace`)."""
        return cls(mass=driveline.mass_matrix(),
                   stiffness=driveline.stiffness_matrix(),
                   damping=driveline.structural_damping(),
                   clutch=driveline.clutch_vector(),
                   upstream=int(driveline.clutch[0]),
                   clutch_factor=driveline.clutch_factor,
                   mu0=driveline.mu0, mu_g=driveline.mu_g,
                   delta_mu=delta_mu, w_op=w_op,
                   slip=w_op if slip is None else float(slip),
                   p_m=driveline.p_m,
                   mean_pressure_damping=driveline.mean_pressure_damping,
                   w_small=w_small, table=table)

    @property
    def limited_drive(self):
        """The drive's torque limit enters the motion."""
        return self.drive >= 0 and np.isfinite(self.drive_limit)

    def channels(self):
        """``B``, shape (n, c): the directions along which the
        nonlinear forces act and whose speeds they depend on: the slip
        (``e``) and, with a limited drive, the drive's body."""
        columns = [self.clutch.astype(float)]
        if self.limited_drive:
            columns.append(np.eye(len(self.clutch))[self.drive])
        return np.column_stack(columns)

    def drive_excess(self, u):
        """The motor torque beyond its linear control, N m, and its
        derivative in the drive's speed deviation ``u`` (rad/s): the
        torque ``clip(T_s - g u, -L, L)`` of ``Judder.Sources.SpeedDrive``
        less the ``T_s - g u`` the linear part holds."""
        linear = self.drive_torque - self.drive_gain * u
        limited = np.clip(linear, -self.drive_limit, self.drive_limit)
        return (limited - linear,
                np.where(limited != linear, self.drive_gain, 0.0))

    def friction(self, w):
        """``mu(w)`` and ``d mu/d w`` of the clutch's characteristic: its
        table where it has one (:meth:`drivelines.friction.FrictionTable.
        curve`), else the curve (:func:`stability.friction.curve`)."""
        if self.table is not None:
            mu, slope = self.table.curve(w)
        else:
            mu, slope = curve(w, self.mu0, self.mu_g, self.delta_mu,
                              self.w_op)
        return mu, np.sign(w) * slope

    def friction_value(self, w):
        """``mu(w)`` alone (:meth:`friction` without the slope, for a
        right-hand side that needs no Jacobian)."""
        if self.table is not None:
            return np.interp(np.abs(w), self.table.slip, self.table.mu)
        return curve_value(w, self.mu0, self.mu_g, self.delta_mu, self.w_op)

    def torque(self, w, t, omega, p_f):
        """Clutch torque ``tau(w, t)`` (N m) and ``d tau/d w``
        (N m s/rad)."""
        mu, slope = self.friction(w)
        m = self.mean_pressure_damping
        load = m * self.p_m + p_f * np.cos(omega * t)
        direction = np.tanh(w / self.w_small)
        d_direction = (1.0 - direction ** 2) / self.w_small
        inner = mu * load + (1.0 - m) * self.mu0 * self.p_m
        return (self.clutch_factor * direction * inner,
                self.clutch_factor * (d_direction * inner
                                      + direction * slope * load))

    def steady_torque(self):
        """Clutch torque of the steady slip without dither, N m."""
        return float(self.torque(np.array(self.slip), 0.0, 0.0, 0.0)[0])

    def dynamic_inverse(self, omega_k):
        """``(K - W^2 M + i W C)^-1 B`` for each ``W`` of ``omega_k``
        (``B``: :meth:`channels`), shape (len, n, c)."""
        channels = self.channels().astype(complex)
        return np.array([np.linalg.solve(
            self.stiffness - w ** 2 * self.mass + 1j * w * self.damping,
            channels) for w in omega_k])


@dataclass(frozen=True)
class Orbit:
    """A periodic orbit of the dithered engagement and its stability.

    Attributes
    ----------
    freq_hz, p_f : float
        Dither frequency (Hz) and amplitude (Pa).
    period_multiple : int
        1 for a T-periodic orbit, 2 for a 2T one (double period).
    slip_harmonics : ndarray, complex, shape (h,)
        ``U_k``, k = 1..h, of the slip-speed deviation at multiples of
        ``freq_hz / period_multiple``, rad/s.
    upstream_harmonics : ndarray, complex, shape (h,)
        The same harmonics of the upstream speed (the bench's channel),
        rad/s.
    upstream_amplitude : float
        Half the peak-to-peak swing of the upstream speed over the orbit,
        rad/s.
    dither_amplitude : float
        ``|W_up|`` at the dither frequency, rad/s.
    slip_range : (float, float)
        Lowest and highest slip over the orbit, rad/s.
    drift_torque : float
        Mean clutch torque beyond the steady slip's, N m: what the dither
        rectifies (positive: more torque to the gearbox side).
    multipliers : ndarray, complex
        Floquet multipliers of the orbit over its period (rigid-body
        directions removed), largest modulus first.
    growth_rate : float
        ``ln|lambda_max| / period``, 1/s.
    kind : str
        How it loses stability: 'stable', 'single-period',
        'double-period' or 'combination' (:mod:`stability.kinds`).
    success : bool
    message : str
    residual : float
        Final residual of the balance, rad/s.
    channel_harmonics : ndarray, complex, shape (h, c)
        The harmonics of every channel's speed (the slip's are
        ``slip_harmonics``; the limited drive's body next).
    drive_saturated : bool
        The drive reaches its torque limit somewhere on the orbit.
    mean_shift : float
        Mean shift of the driven bodies' speed, and so of the slip,
        rad/s (0 without a limited drive): where the limit cuts the
        motor's torque, its control lowers their speed until the mean
        torque is the steady one again.
    """

    freq_hz: float
    p_f: float
    period_multiple: int
    slip_harmonics: np.ndarray
    upstream_harmonics: np.ndarray
    upstream_amplitude: float
    dither_amplitude: float
    slip_range: tuple
    drift_torque: float
    multipliers: np.ndarray
    growth_rate: float
    kind: str
    success: bool
    message: str
    residual: float
    channel_harmonics: np.ndarray = None
    drive_saturated: bool = False
    mean_shift: float = 0.0

    @property
    def stable(self):
        """The orbit attracts: every multiplier inside the unit circle."""
        return self.growth_rate < 0

    @property
    def subharmonic_share(self):
        """Share of the upstream speed at the odd half-harmonics (0 for a
        T-orbit)."""
        if self.period_multiple == 1:
            return 0.0
        odd = np.abs(self.upstream_harmonics[0::2])
        return float(np.sqrt((odd ** 2).sum()
                             / max((np.abs(self.upstream_harmonics)
                                    ** 2).sum(), 1e-300)))


class _Balance:
    """The condensed harmonic balance of one dither frequency.

    The unknowns are the harmonics ``Y`` (shape (h, c)) of the speeds
    along the model's channels (:meth:`EngagementModel.channels`: the
    slip, and the limited drive's body), laid out as ``[Re Y, Im Y]``
    with each channel's ``h`` harmonics together. The forces along the
    channels are ``q_0 = -tau(w_s + y_0, t)`` (the clutch) and ``q_1 =``
    :meth:`EngagementModel.drive_excess` ``(y_1)``, and the balance is
    ``Y_k = G(k nu) Q_k`` with ``G(W) = i W B^T (K - W^2 M + i W C)^-1 B``.
    """

    def __init__(self, model, freq_hz, harmonics, period_multiple):
        self.model = model
        self.omega = 2 * np.pi * freq_hz
        self.base = self.omega / period_multiple
        self.period_multiple = period_multiple
        self.h = harmonics * period_multiple
        self.channels = model.channels()
        self.c = self.channels.shape[1]
        k = np.arange(1, self.h + 1)
        samples = max(8 * self.h, 64)
        self.t = np.arange(samples) * (2 * np.pi / self.base) / samples
        phase = np.outer(k, self.base * self.t)
        self.cos, self.sin = np.cos(phase), np.sin(phase)
        self.analysis = np.exp(-1j * phase) * 2.0 / samples
        self.basis = np.hstack([self.cos.T, -self.sin.T])
        inverse = model.dynamic_inverse(k * self.base)
        frequency = 1j * k * self.base
        self.gain = frequency[:, None, None] * np.einsum(
            "nc,knd->kcd", self.channels, inverse)
        self.upstream_gain = frequency[:, None] * inverse[:, model.upstream]
        self.steady = model.steady_torque()

    @property
    def size(self):
        """Number of real unknowns: the harmonics, and with a limited
        drive the mean shift of the speed of the bodies it turns."""
        return 2 * self.h * self.c + (self.c > 1)

    def harmonics(self, x):
        """``Y``, shape (h, c), of the unknowns ``x``."""
        half = self.h * self.c
        return (x[:half] + 1j * x[half:2 * half]).reshape(self.c, self.h).T

    def mean_shift(self, x):
        """Mean shift of the driven bodies' speed (and of the slip),
        rad/s."""
        return float(x[-1]) if self.c > 1 else 0.0

    def unknowns(self, Y, mean_shift=0.0):
        """``x`` of the harmonics ``Y`` (shape (h, c)) and the mean
        shift."""
        flat = Y.T.ravel()
        return np.concatenate([flat.real, flat.imag]
                              + ([[mean_shift]] if self.c > 1 else []))

    def speeds(self, x):
        """The channels' speed deviations over the period, shape
        (c, samples)."""
        Y = self.harmonics(x)
        return Y.real.T @ self.cos - Y.imag.T @ self.sin + \
            self.mean_shift(x)

    def forces(self, y, p_f):
        """The channels' forces and their derivatives in the channels'
        speeds (shape (c, samples) each), and the clutch torque."""
        model = self.model
        tau, dtau = model.torque(model.slip + y[0], self.t, self.omega, p_f)
        q, dq = [-tau], [-dtau]
        if self.c > 1:
            excess, d_excess = model.drive_excess(y[1])
            q.append(excess)
            dq.append(d_excess)
        return np.array(q), np.array(dq), tau

    def residual(self, x, p_f):
        """Residual (real), its Jacobian in ``x`` and in ``p_f``."""
        h, c = self.h, self.c
        Y = self.harmonics(x)
        y = self.speeds(x)
        q, dq, _ = self.forces(y, p_f)
        Q = (self.analysis @ q.T)                     # (h, c)
        R = Y - np.einsum("kij,kj->ki", self.gain, Q)
        J = np.zeros((h * c, self.size), dtype=complex)
        eye = np.eye(h)
        for j in range(c):
            # d Q_j / d (Re Y_j, Im Y_j), shape (h, 2h)
            dQ = self.analysis @ (dq[j][:, None] * self.basis)
            for i in range(c):
                block = -self.gain[:, i, j][:, None] * dQ
                if i == j:
                    block[:, :h] += eye
                    block[:, h:] += 1j * eye
                J[i * h:(i + 1) * h, j * h:(j + 1) * h] = block[:, :h]
                J[i * h:(i + 1) * h,
                  (c + j) * h:(c + j + 1) * h] = block[:, h:]
        model = self.model
        mu, _ = model.friction(model.slip + y[0])
        dq_dp = -(model.clutch_factor * np.tanh((model.slip + y[0])
                                                / model.w_small)
                  * mu * np.cos(self.omega * self.t))
        Rp = -self.gain[:, :, 0] * (self.analysis @ dq_dp)[:, None]
        R, Rp = R.T.ravel(), Rp.T.ravel()
        R, J, Rp = (np.concatenate([R.real, R.imag]),
                    np.vstack([J.real, J.imag]),
                    np.concatenate([Rp.real, Rp.imag]))
        if c == 1:
            return R, J, Rp
        # the mean: the driven bodies' torques balance on average
        # (:attr:`EngagementModel.drive_damping`), scaled to rad/s
        damping = model.drive_damping
        shifted = -np.einsum("kij,kj->ki", self.gain,
                             self.analysis @ dq.T).T.ravel()
        J[:, -1] = np.concatenate([shifted.real, shifted.imag])
        mean = (q.mean(axis=1).sum() + self.steady) / damping - x[-1]
        row = np.zeros(self.size)
        for j in range(c):
            weights = (dq[j][:, None] * self.basis).mean(axis=0) / damping
            row[j * h:(j + 1) * h] = weights[:h]
            row[(c + j) * h:(c + j + 1) * h] = weights[h:]
        row[-1] = dq.mean(axis=1).sum() / damping - 1.0
        return (np.append(R, mean), np.vstack([J, row]),
                np.append(Rp, dq_dp.mean() / damping))

    def newton(self, x, p_f):
        scale = max(np.abs(x).max(), 1.0)
        for _ in range(_MAX_NEWTON):
            R, J, _ = self.residual(x, p_f)
            norm = np.abs(R).max()
            if norm < _TOLERANCE * scale:
                return x, norm, True
            try:
                step = np.linalg.solve(J, -R)
            except np.linalg.LinAlgError:
                return x, norm, False
            x = x + step
            if not np.all(np.isfinite(x)):
                return x, np.inf, False
            scale = max(np.abs(x).max(), 1.0)
        R = self.residual(x, p_f)[0]
        norm = np.abs(R).max()
        return x, norm, norm < _TOLERANCE * scale * 1e3

    def orbit(self, x, p_f, success, residual, message=""):
        model = self.model
        Y = self.harmonics(x)
        y = self.speeds(x)
        q, _, tau = self.forces(y, p_f)
        Q = self.analysis @ q.T
        upstream = np.einsum("kj,kj->k", self.upstream_gain, Q)
        speed = upstream.real @ self.cos - upstream.imag @ self.sin
        at_dither = upstream[self.period_multiple - 1]
        multipliers = self.multipliers(Y, self.mean_shift(x), p_f)
        period = 2 * np.pi / self.base
        lead = multipliers[0] if len(multipliers) else 1.0
        growth = float(np.log(max(abs(lead), 1e-300)) / period)
        w = model.slip + y[0]
        return Orbit(freq_hz=self.omega / (2 * np.pi), p_f=float(p_f),
                     period_multiple=self.period_multiple,
                     slip_harmonics=Y[:, 0], upstream_harmonics=upstream,
                     upstream_amplitude=float(0.5 * np.ptp(speed)),
                     dither_amplitude=float(abs(at_dither)),
                     slip_range=(float(w.min()), float(w.max())),
                     drift_torque=float(np.mean(tau) - self.steady),
                     multipliers=multipliers, growth_rate=growth,
                     kind=KINDS[int(classify(lead))], success=bool(success),
                     message=message or ("converged" if success else
                                         "the balance did not converge"),
                     residual=float(residual), channel_harmonics=Y,
                     mean_shift=self.mean_shift(x),
                     drive_saturated=bool(
                         self.c > 1 and np.any(self.forces(y, p_f)[1][1]
                                               != 0)))

    def multipliers(self, Y, mean_shift, p_f):
        """Floquet multipliers of the variational equation about the
        orbit over its period (fourth-order Magnus, rigid-body directions
        removed)."""
        model = self.model
        n = len(model.clutch)
        period = 2 * np.pi / self.base
        steps = _MONODROMY_STEPS * self.period_multiple
        h = period / steps
        gauss = 0.5 + np.array([-1, 1]) * np.sqrt(3) / 6
        times = (np.arange(steps)[:, None] + gauss[None, :]) * h
        k = np.arange(1, self.h + 1)
        phase = np.multiply.outer(times, k * self.base)
        y = np.stack([np.cos(phase) @ Y[:, j].real
                      - np.sin(phase) @ Y[:, j].imag
                      for j in range(self.c)]) + mean_shift
        _, slope = model.torque(model.slip + y[0], times, self.omega, p_f)
        slopes = [-slope]
        if self.c > 1:
            slopes.append(model.drive_excess(y[1])[1])
        minv = np.linalg.inv(model.mass)
        base = np.zeros((2 * n, 2 * n))
        base[:n, n:] = np.eye(n)
        base[n:, :n] = -minv @ model.stiffness
        base[n:, n:] = -minv @ model.damping
        A = np.broadcast_to(base, times.shape + base.shape).copy()
        for j, channel_slope in enumerate(slopes):
            coupling = np.zeros((2 * n, 2 * n))
            b = self.channels[:, j]
            coupling[n:, n:] = minv @ np.outer(b, b)
            A += channel_slope[..., None, None] * coupling
        A1, A2 = A[:, 0], A[:, 1]
        magnus = 0.5 * h * (A1 + A2) + (np.sqrt(3) / 12) * h ** 2 * (
            A2 @ A1 - A1 @ A2)
        phi = np.eye(2 * n)
        with np.errstate(over="ignore", invalid="ignore"):
            for step in _batched_expm(magnus):
                phi = step @ phi
        if not np.all(np.isfinite(phi)):
            # a period so long that the variational equation's growth
            # over it exceeds floating point: no multipliers to give
            freq = self.base / (2 * np.pi)
            raise JudderError(
                f"the orbit's monodromy over one period ({period:.4g} s) "
                f"overflows at `freq_hz` {freq:g} Hz, so its stability "
                "cannot be computed; allowed: a higher `freq_hz` (a "
                "shorter period)")
        rigid = _rigid_directions(model.stiffness, n)
        if rigid.shape[1]:
            q = scipy.linalg.null_space(rigid.T)
            phi = q.T @ phi @ q
        values = np.linalg.eigvals(phi)
        return values[np.argsort(-np.abs(values))]


def _batched_expm(matrices, order=12):
    """``exp`` of each of ``matrices`` (shape (m, n, n)): scaling by a
    power of 2 to a 1-norm of at most 1/2, Taylor series of ``order``
    (truncation below 1e-13) and squaring, vectorised over the batch
    (SciPy's ``expm`` treats a batch one matrix at a time)."""
    norm = np.abs(matrices).sum(axis=1).max()
    squarings = max(0, int(np.ceil(np.log2(max(norm, 1e-300) / 0.5))))
    scaled = matrices / 2.0 ** squarings
    result = np.broadcast_to(np.eye(matrices.shape[-1]),
                             matrices.shape).copy()
    term = result.copy()
    for k in range(1, order + 1):
        term = term @ scaled / k
        result += term
    for _ in range(squarings):
        result = result @ result
    return result


def _rigid_directions(stiffness, n):
    """Constant-angle directions ``(x, 0)`` with ``K x = 0``, shape
    (2n, r)."""
    null = scipy.linalg.null_space(stiffness, rcond=1e-10)
    return np.vstack([null, np.zeros_like(null)])


def periodic_orbit(model, freq_hz, p_f, harmonics=DEFAULT_HARMONICS,
                   period_multiple=1, start=None):
    """The periodic orbit of the dithered engagement at one setting.

    Parameters
    ----------
    model : EngagementModel
    freq_hz : float
        Dither frequency, Hz.
    p_f : float
        Dither amplitude, Pa.
    harmonics : int
        Harmonics of the dither frequency kept.
    period_multiple : {1, 2}
        1: the T-periodic orbit (the forced response grown out of zero);
        2: a 2T orbit, seeded from ``start``.
    start : Orbit, optional
        An orbit to start Newton's method from (its harmonics; a T-orbit
        seeds a 2T one with its half-harmonics set by the leading
        multiplier's direction, see :func:`double_period_orbit`).

    Returns
    -------
    Orbit
        ``success`` False when the balance did not converge.
    """
    balance = _Balance(model, freq_hz, harmonics, period_multiple)
    x = np.zeros(balance.size)
    if start is not None:
        x = _seed(balance, start)
    x, residual, success = balance.newton(x, p_f)
    if not success and start is None:
        # from zero up in amplitude: continue from a small dither
        branch = continue_orbit(model, freq_hz, [p_f * s for s in
                                                 (0.25, 0.5, 0.75, 1.0)],
                                harmonics=harmonics)
        return branch.orbits[-1]
    return balance.orbit(x, p_f, success, residual)


#: Smallest drift of the held slip over a run that :func:`drifted_orbit`
#: follows, rad/s: 5 % of the bench curve's linear range (about 1 rad/s),
#: where its slope has changed by well under 1 %.
_SMALLEST_DRIFT = 0.05


def drifted_orbit(model, orbit, steps=2, harmonics=DEFAULT_HARMONICS):
    """The T-orbit where the held slip has drifted to after
    ``model.drift_time``, and its model.

    The flat-friction load of the bench balances the clutch's steady
    torque only: the torque the dither rectifies (``orbit.drift_torque``)
    turns the gearbox side, and the mean slip moves slowly along the
    friction curve, ``dw_s/dt = -drift(w_s) / J`` with ``J`` the
    ``load_inertia`` (quasi-static: each instant's orbit at its slip).
    Heun's method in ``steps`` steps, each orbit solved from the last
    (4 steps moved the amplitudes of the fitted set's drifting settings by
    under 1 % against 2).

    Parameters
    ----------
    model : EngagementModel
    orbit : Orbit
        The T-orbit at ``model.slip``.

    Returns
    -------
    (Orbit, EngagementModel)
        ``orbit`` and ``model`` themselves where nothing drifts (no
        ``drift_time`` or ``load_inertia``, a failed orbit, or a drift of
        under :data:`_SMALLEST_DRIFT` over the run).
    """
    from dataclasses import replace
    if model.drift_time <= 0 or model.load_inertia <= 0 or \
            not orbit.success or orbit.period_multiple != 1:
        return orbit, model
    rate = -orbit.drift_torque / model.load_inertia
    if abs(rate) * model.drift_time < _SMALLEST_DRIFT:
        return orbit, model
    h = model.drift_time / steps
    at, here = model, orbit
    for _ in range(steps):
        trial_model = replace(at, slip=at.slip + h * rate)
        trial = periodic_orbit(trial_model, here.freq_hz, here.p_f,
                               harmonics, start=here)
        if not trial.success:
            return here, at
        slope = -trial.drift_torque / model.load_inertia
        at = replace(at, slip=at.slip + 0.5 * h * (rate + slope))
        here = periodic_orbit(at, here.freq_hz, here.p_f, harmonics,
                              start=trial)
        if not here.success:
            return trial, trial_model
        rate = -here.drift_torque / model.load_inertia
    return here, at


def _seed(balance, orbit):
    """Newton's start for ``balance`` from another orbit's harmonics."""
    Y = np.zeros((balance.h, balance.c), dtype=complex)
    known = orbit.channel_harmonics
    if known is None or known.shape[1] != balance.c:
        known = np.zeros((len(orbit.slip_harmonics), balance.c),
                         dtype=complex)
        known[:, 0] = orbit.slip_harmonics
    if orbit.period_multiple == balance.period_multiple:
        count = min(len(known), balance.h)
        Y[:count] = known[:count]
    else:
        # a T-orbit's harmonic k is the 2T orbit's 2k
        even = known[:balance.h // 2]
        Y[1::2][:len(even)] = even
    return balance.unknowns(Y, orbit.mean_shift)


def double_period_orbit(model, orbit, harmonics=DEFAULT_HARMONICS,
                        amplitudes=(1.0, 4.0, 16.0)):
    """The 2T orbit that grows out of a T-orbit unstable through -1.

    Newton's method starts from the T-orbit with a half-harmonic of the
    slip speed added (``amplitudes`` in rad/s, two phases); the first
    solution with a half-harmonic share above 1 % is returned, else None.
    """
    balance = _Balance(model, orbit.freq_hz, harmonics, 2)
    base = _seed(balance, orbit)
    for amplitude in amplitudes:
        for phase in (0.0, 0.5 * np.pi):
            x = base.copy()
            x[0] += amplitude * np.cos(phase)
            x[balance.size // 2] += amplitude * np.sin(phase)
            x, residual, success = balance.newton(x, orbit.p_f)
            if not success:
                continue
            found = balance.orbit(x, orbit.p_f, success, residual)
            if found.subharmonic_share > 0.01:
                return found
    return None


@dataclass(frozen=True)
class OrbitBranch:
    """Orbits of one dither frequency continued in ``p_f``.

    Attributes
    ----------
    orbits : list of Orbit
        Along the branch, in order (``p_f`` may turn back at a fold).
    folds : list of int
        Indices where ``p_f`` turns back (saddle-node points).
    complete : bool
        The branch reached the last amplitude asked for.
    """

    orbits: list
    folds: list = field(default_factory=list)
    complete: bool = True


def continue_orbit(model, freq_hz, p_f_values, harmonics=DEFAULT_HARMONICS,
                   start=None, max_steps=400):
    """T-orbits of one frequency from the first to the last of
    ``p_f_values`` by pseudo-arclength continuation, with an orbit at
    each of them.

    The branch is followed through folds (``p_f`` turning back, where two
    orbits meet and the T-orbit jumps), so that stable and unstable parts
    are both drawn; at each requested ``p_f`` the orbit of the branch's
    first pass is kept.

    Parameters
    ----------
    model : EngagementModel
    freq_hz : float
    p_f_values : sequence of float
        Increasing amplitudes, Pa (the first may be 0).
    start : Orbit, optional
        Orbit at ``p_f_values[0]`` (default: solved from rest).

    Returns
    -------
    OrbitBranch
        ``orbits`` holds the branch at the requested amplitudes and at the
        folds, in branch order.
    """
    balance = _Balance(model, freq_hz, harmonics, 1)
    targets = [float(p) for p in p_f_values]
    x = np.zeros(balance.size) if start is None else _seed(balance, start)
    x, residual, success = balance.newton(x, targets[0])
    orbits = [balance.orbit(x, targets[0], success, residual)]
    if not success:
        return OrbitBranch(orbits, complete=False)
    span = max(targets[-1] - targets[0], 1e-9)
    scale = _amplitude_scale(balance, x, targets[-1])
    y = np.concatenate([x / scale, [targets[0] / span]])
    tangent = _tangent(balance, y, scale, span, None)
    ds = 0.05
    folds, next_target, steps = [], 1, 0
    while next_target < len(targets) and steps < max_steps:
        steps += 1
        guess = y + ds * tangent
        solved, ok = _corrector(balance, guess, y, tangent, ds, scale, span)
        if not ok:
            ds *= 0.5
            if ds < 1e-6:
                break
            continue
        new_tangent = _tangent(balance, solved, scale, span, tangent)
        p_old, p_new = y[-1] * span, solved[-1] * span
        # requested amplitudes crossed in this step, on the first pass
        while next_target < len(targets) and \
                min(p_old, p_new) <= targets[next_target] <= max(p_old,
                                                                 p_new) \
                and p_new > p_old:
            target = targets[next_target]
            share = (target - p_old) / (p_new - p_old)
            xt = (y[:-1] + share * (solved[:-1] - y[:-1])) * scale
            xt, residual, success = balance.newton(xt, target)
            orbits.append(balance.orbit(xt, target, success, residual))
            next_target += 1
        if new_tangent[-1] * tangent[-1] < 0:
            x_fold = solved[:-1] * scale
            orbits.append(balance.orbit(x_fold, p_new, True, 0.0,
                                        "fold: p_f turns back"))
            folds.append(len(orbits) - 1)
        y, tangent = solved, new_tangent
        ds = min(ds * 1.5, 0.2)
    return OrbitBranch(orbits, folds, complete=next_target >= len(targets))


def _amplitude_scale(balance, x, p_f):
    """Slip-speed scale of the harmonics, rad/s (the linear forced
    response at ``p_f``, at least 1)."""
    linear = abs(balance.gain[balance.period_multiple - 1, 0, 0]) * \
        balance.model.clutch_factor * balance.model.mu0 * p_f
    return max(float(linear), np.abs(x).max(), 1.0)


def _tangent(balance, y, scale, span, previous):
    """Unit tangent of the branch at ``y`` (scaled harmonics and p_f),
    oriented along ``previous`` (or towards higher ``p_f``)."""
    _, J, Rp = balance.residual(y[:-1] * scale, y[-1] * span)
    augmented = np.hstack([J * scale, (Rp * span)[:, None]])
    tangent = scipy.linalg.null_space(augmented)[:, 0]
    reference = previous if previous is not None else \
        np.eye(len(y))[-1]
    if tangent @ reference < 0:
        tangent = -tangent
    return tangent


def _corrector(balance, guess, y, tangent, ds, scale, span):
    """Newton's method on the balance plus the arclength condition."""
    z = guess.copy()
    for _ in range(_MAX_NEWTON):
        R, J, Rp = balance.residual(z[:-1] * scale, z[-1] * span)
        arc = tangent @ (z - y) - ds
        if np.abs(R).max() < _TOLERANCE * scale and abs(arc) < 1e-12:
            return z, True
        full = np.vstack([np.hstack([J * scale, (Rp * span)[:, None]]),
                          tangent[None, :]])
        try:
            step = np.linalg.solve(full, -np.concatenate([R, [arc]]))
        except np.linalg.LinAlgError:
            return z, False
        z = z + step
        if not np.all(np.isfinite(z)):
            return z, False
    R = balance.residual(z[:-1] * scale, z[-1] * span)[0]
    return z, bool(np.abs(R).max() < 1e-7 * scale)
