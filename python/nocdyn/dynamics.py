"""The inverse dynamics of a Robot on sample arrays, bound one to one to the library's
algorithms: the actuator variables and forces (eqs. 5, 20), the NOC matrices (eq. 23), their
exact derivatives, the joint reactions, the regressor (tau = Y pi) and the linearised model.
One sample is three arrays of shape (3,); a batch, three of shape (N, 3), runs in C++ with the
GIL released. A batch's errors name the sample K, numbered from 1 (row K - 1 of the arrays)."""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from ._guards import _MAX_THREADS, _floats, _input, _integer, _outputs, _vocabulary
from ._nocdyn import Error

__all__ = ["InverseDynamics", "InverseDynamicsMatrices", "ActuatorDerivatives", "LinearModel"]


InverseDynamics = namedtuple("InverseDynamics", ["u", "du", "ddu", "tau"])
InverseDynamics.__doc__ = """Inverse dynamics of one sample (arrays of shape (n,)) or a batch ((N, n)).

u: actuator variables [m or rad]; du: their rates [m/s or rad/s]; ddu: accelerations
[m/s^2 or rad/s^2]; tau: actuator forces [N or N m] (eq. 20; minimum-norm when redundant)."""

ActuatorDerivatives = namedtuple("ActuatorDerivatives",
                                 ["u", "du", "ddu", "u_p", "du_p", "du_dp", "ddu_p", "ddu_dp", "ddu_ddp"])
ActuatorDerivatives.__doc__ = """The actuator variables of one sample and their exact derivatives.

u, du, ddu: as InverseDynamics, shape (n,). u_p = d u/d p, du_p = d du/d p, du_dp = d du/d dp,
ddu_p = d ddu/d p, ddu_dp = d ddu/d dp, ddu_ddp = d ddu/d ddp: shape (n, 3), row a actuator
a + 1, columns the pose order [x, y, theta]. du_dp = ddu_ddp = u_p (du and ddu are linear in
dp and ddp with the actuation map A S(c) as coefficients)."""


def _derivative_inputs(p, dp, ddp):
    """(False, (p, dp, ddp)) of one sample, shape (3,) each, or (True, (p, dp, ddp)) of a batch,
    shape (N, 3) each, read in place whatever their memory order (NaN allowed: a failed sample)."""
    p_arr = _floats(p, "p")
    if p_arr.ndim == 1:
        return False, (p_arr, _floats(dp, "dp"), _floats(ddp, "ddp"))
    if p_arr.ndim != 2:
        raise Error(f"p: expected shape (3,) or (N, 3), got {p_arr.shape}")
    n = p_arr.shape[0]
    return True, (_input(p_arr, "p", (None, 3), finite=False), _input(dp, "dp", (n, 3), finite=False),
                  _input(ddp, "ddp", (n, 3), finite=False))


def _lift_task(p, dp, ddp):
    """A two-DOF robot's task samples [x, y] (shape (2,) or (N, 2)) as the core's poses
    [x, y, theta] with theta = 0 and its rates 0 (the task map E; the rotation is no
    coordinate)."""
    p_arr = _floats(p, "p")
    if p_arr.ndim not in (1, 2) or p_arr.shape[-1] != 2:
        raise Error(f"p: expected shape (2,) or (N, 2) for a two-DOF robot (columns x, y), got {p_arr.shape}")
    shape = p_arr.shape
    lifted = []
    for x, name in ((p_arr, "p"), (dp, "dp"), (ddp, "ddp")):
        a = _input(x, name, shape if len(shape) == 1 else (shape[0], 2), finite=False)
        full = np.zeros(shape[:-1] + (3,))
        full[..., :2] = a
        lifted.append(full)
    return lifted


class LinearModel(tuple):
    """A linearised model (Robot.linearize): the tuple (A, B), or (A, B, C, D) when an output was
    asked for, with the attributes A, B, C, D, ``inputs`` (per column of B: "tau" an actuator
    force, "uc" a drive's commanded position) and ``model`` ("rigid" or "lumped")."""

    def __new__(cls, items, A, B, C, D, inputs, model):
        self = super().__new__(cls, items)
        self.A, self.B, self.C, self.D = A, B, C, D
        self.inputs = tuple(inputs)
        self.model = model
        return self


InverseDynamicsMatrices = namedtuple("InverseDynamicsMatrices", ["u", "du", "ddu", "tau", "I", "C", "T"])
InverseDynamicsMatrices.__doc__ = """Inverse dynamics of one sample with the NOC matrices (eq. 23).

u, du, ddu, tau: as InverseDynamics, shape (n,). I: (3, 3) generalized inertia in the
independent coordinates (the actuator variables for 3 actuators, the platform pose when
redundant) [kg, kg m, kg m^2]; C: (3, 3) Coriolis matrix with dI/dt = C + C^T; T: (bodies, 3, 3)
twist-shaping matrices T_i (t_i = T_i v, eq. 22), bodies numbered as the paper does (first
bodies of limbs 1..m, second bodies, then the platform)."""


class RobotDynamics:
    """The sample-array algorithms of nocdyn.Robot (its base class; use nocdyn.Robot)."""

    __slots__ = ()

    # --- inverse dynamics -------------------------------------------------------------
    @_vocabulary
    def inverse_dynamics(self, p, dp, ddp, *, matrices=False, out=None, threads=1, check=True, check_limits=True):
        """Actuator variables, rates, accelerations and forces for platform motions.

        A two-DOF robot (motion: translation) takes p, dp, ddp of shape (2,) or (N, 2), columns
        x, y of the tool point (matrices=False only).

        One sample: p, dp, ddp of shape (3,) ([x, y, theta], its rate and acceleration) give
        InverseDynamics(u, du, ddu, tau), each of shape (n,). With matrices=True (one sample
        only) the full NOC path also returns I, C (3, 3) and T (bodies, 3, 3)
        (InverseDynamicsMatrices; when the robot is redundant their pose rows and columns are
        in the order [x, y, theta], and T_i's rows, body i's twist, are [v_x, v_y, omega]).

        Batch: p, dp, ddp of shape (N, 3), float64, give u, du, ddu, tau of shape (N, n). The
        inputs are read in place, whatever their memory order (C, Fortran, or a strided view:
        no copy; reversed, misaligned or byte-swapped arrays are copied); another dtype raises
        TypeError, a NaN or infinite input nocdyn.Error. The results are written into `out`, a
        tuple of four (N, n) float64 arrays of the same memory order, when given (and
        returned), else into new C-ordered arrays; outputs that overlap one another, themselves
        or an input are refused. The GIL is released during the computation, so other Python
        threads run meanwhile. threads (0..1024) > 1 splits the samples over that many C++
        threads, at most one per hardware thread and sample (0: one per hardware thread).

        A sample out of reach or singular raises nocdyn.Error "sample K: <reason>" (K from 1: row K - 1; the first
        such sample; its row, like every failed one, is NaN), and so does a result that is not
        finite (rates or accelerations so large that the forces overflow). check=False returns
        instead, leaving NaN rows for the failed samples.

        Limits, as `nocdyn inverse-dynamics` checks them: with check_limits=True (the default) a
        sample where a joint leaves its range or exceeds its velocity limit, or an actuator its
        effort, raises nocdyn.Error with the command line's reason ("sample K: <reason>" for a
        batch: the first such sample; the outputs are filled all the same). They are checked on
        the results u, du, tau when every limited joint is actuated (no second inverse dynamics;
        a batch checks them inside its kernel, on values still in registers, at no measurable
        cost), else by the full path at every sample (a range on a passive joint needs its q,
        which the batch's kernel does not compute); check_limits=False checks none.
        """
        threads = min(_integer(threads, "threads", 0, 2**63), _MAX_THREADS)
        if self._core.task_dimension == 2:
            # a two-DOF robot (motion: translation): p, dp, ddp over [x, y]; one sample lifted
            # through E here, a batch read in place and lifted in C++ slice by slice
            if matrices:
                raise Error("matrices: not available for a two-DOF robot (motion: translation) yet")
            if _floats(p, "p").ndim == 2:
                return self._batch(self._core._inverse_dynamics_task_batch, 2, p, dp, ddp, out, threads, check,
                                   check_limits)
            p, dp, ddp = _lift_task(p, dp, ddp)
        p_arr = _floats(p, "p")
        if p_arr.ndim == 1:
            if out is not None:
                raise Error("out: only for a batch of (N, 3) arrays")
            # the compiled part checks that the results are finite (check): no pass here
            result = self._core._inverse_dynamics_sample(p_arr, dp, ddp, bool(matrices), bool(check_limits),
                                                         bool(check))
            return InverseDynamicsMatrices(*result) if matrices else InverseDynamics(*result)
        if matrices:
            raise Error("matrices: only for one sample (p of shape (3,))")
        if p_arr.ndim != 2:
            raise Error(f"p: expected shape (3,) or (N, 3), got {p_arr.shape}")
        return self._batch(self._core._inverse_dynamics_batch, 3, p_arr, dp, ddp, out, threads, check, check_limits)

    def _batch(self, run, columns, p, dp, ddp, out, threads, check, check_limits):
        """inverse_dynamics of a batch, p, dp, ddp of shape (N, columns), through the compiled
        `run`: columns 3 ([x, y, theta]) or 2 (a two-DOF robot's [x, y], lifted in C++)."""
        p_arr = _input(p, "p", (None, columns), finite=False)
        n = p_arr.shape[0]
        dp_arr = _input(dp, "dp", (n, columns), finite=False)
        ddp_arr = _input(ddp, "ddp", (n, columns), finite=False)
        shape = (n, self.actuators)
        if out is None:
            out = tuple(np.empty(shape) for _ in range(4))
        else:
            out = _outputs(out, ("u", "du", "ddu", "tau"), shape, ((p_arr, "p"), (dp_arr, "dp"), (ddp_arr, "ddp")))
        # the compiled batch counts a sample whose results overflow as failed (its row NaN), and
        # raises the library's words (describeFailure, describeLimits)
        run(p_arr, dp_arr, ddp_arr, *out, threads=threads, check=bool(check), check_limits=bool(check_limits))
        return InverseDynamics(*out)

    @_vocabulary
    def inverse_dynamics_derivatives(self, p, dp, ddp, *, threads=1, check=True):
        """Exact first derivatives of the actuator forces: (d tau/d p, d tau/d dp, d tau/d ddp).

        One sample, p, dp, ddp of shape (3,), gives three arrays of shape (n, 3); a batch,
        shape (N, 3) each, three of shape (N, n, 3). Row a is actuator a + 1, columns the pose
        order [x, y, theta] of inverse_dynamics; d tau/d ddp is the mass matrix mapped to the
        actuators. Forward-mode automatic differentiation: exact to rounding. Coulomb friction
        is differentiated with its sign held (at a joint rate of exactly 0 its force and
        derivative are 0). Errors and threads as in inverse_dynamics. A two-DOF robot (motion:
        translation) takes shape (2,) or (N, 2), columns x, y, and its derivatives have the
        columns x, y (the task map E: d tau/d p_t = d tau/d p E).
        """
        threads = min(_integer(threads, "threads", 0, 2**63), _MAX_THREADS)
        two_dof = self._core.task_dimension == 2
        if two_dof:
            p, dp, ddp = _lift_task(p, dp, ddp)  # [x, y, 0]: theta is no coordinate
        batch, inputs = _derivative_inputs(p, dp, ddp)
        if not batch:
            result = self._core._inverse_dynamics_derivatives_sample(*inputs)
        else:
            result = self._core._inverse_dynamics_derivatives_batch(*inputs, threads=threads, check=bool(check))
        return tuple(d[..., :2] for d in result) if two_dof else result

    @_vocabulary
    def actuator_derivatives(self, p, dp, ddp, *, threads=1, check=True):
        """Exact first derivatives of the actuator variables u, du, ddu of one sample (p, dp,
        ddp of shape (3,)): an ActuatorDerivatives of u, du, ddu (n,) and d u/d p, d du/d p,
        d du/d dp, d ddu/d p, d ddu/d dp, d ddu/d ddp (n, 3), columns in the pose order
        [x, y, theta]. The actuated joints' rates and accelerations by the same forward-mode
        automatic differentiation as inverse_dynamics_derivatives: exact to rounding. A batch,
        p, dp, ddp of shape (N, 3), gives u, du, ddu of shape (N, n) and the derivatives of
        shape (N, n, 3), each row the sample's own values to the bit. Errors, check and threads
        as in inverse_dynamics (check=False: a failed sample's rows are NaN). A two-DOF robot
        (motion: translation) takes shape (2,) or (N, 2), columns x, y, and its derivatives have
        the columns x, y.
        """
        threads = min(_integer(threads, "threads", 0, 2**63), _MAX_THREADS)
        two_dof = self._core.task_dimension == 2
        if two_dof:
            p, dp, ddp = _lift_task(p, dp, ddp)  # [x, y, 0]: theta is no coordinate
        batch, inputs = _derivative_inputs(p, dp, ddp)
        if not batch:
            result = self._core._actuator_derivatives_sample(*inputs)
        else:
            result = self._core._actuator_derivatives_batch(*inputs, threads=threads, check=bool(check))
        if two_dof:  # u, du, ddu as they are; the derivatives over x, y
            result = tuple(r if k < 3 else r[..., :2] for k, r in enumerate(result))
        return ActuatorDerivatives(*result)

    @_vocabulary
    def linearize(self, p, dp, tau, *, output=None, compliance="auto"):
        """The robot linearised at the state (p, dp) ([x, y, theta] and its rate) under the
        actuator forces tau (n,): (A, B) with the state x = [p; dp] = [x, y, theta, dx/dt, dy/dt,
        dtheta/dt] and the input u, dx/dt = A x + B u (deviations from the operating point),
        A (6, 6), B (6, n), from the exact derivatives of the forward dynamics. output=
        "acceleration" or "actuators" also returns C and D of that output (y = C x + D u, y = ddp
        in the order [x, y, theta], or the actuator variables A_p p): (A, B, C, D).

        compliance, as ``nocdyn frequency-response --compliance``: "rigid" the rigid model, every
        input an actuator force [N or N m]; "lumped" the compliant lumped model of the joint and
        drive stiffness and elastic links the robot file declares (an error when it declares
        none); "auto" (default) lumped when the file declares compliance, else rigid. The lumped
        model's springs are massless and quasi-static and its bodies rigid, carried by the
        platform's pose: its state is the same x = [p; dp] (6 states; A's lower left block
        gains -M_p^-1 K, K the Cartesian stiffness of Robot.stiffness, so that A's
        eigenfrequencies at rest without gravity are Robot.natural_frequencies), and its input a
        is drive a's commanded position (its spring's rest position) [m or rad] when the drive
        has a stiffness (or none is given and the drive is locked), its force when its
        stiffness is 0.

        The result is a LinearModel: a tuple (A, B) or (A, B, C, D) with the attributes A, B, C,
        D, ``inputs`` (per column of B "tau" for a force, "uc" for a commanded drive position:
        the command line's channel names) and ``model`` ("rigid" or "lumped").

        A two-DOF robot (motion: translation) takes p and dp of shape (2,) ([x, y] and its rate):
        its state is x = [x, y, dx/dt, dy/dt], A (4, 4), B (4, n), the output "acceleration"
        [d2x/dt2, d2y/dt2]; its model is rigid (a lumped compliant two-DOF model is not built:
        compliance="lumped", or "auto" on a file that declares compliance, raises nocdyn.Error).
        """
        if self._core.task_dimension == 2:  # the state [x, y, dx/dt, dy/dt]: theta is no coordinate
            p_arr = _floats(p, "p")
            if p_arr.shape != (2,):
                raise Error(f"p: expected shape (2,) for a two-DOF robot ([x, y]), got {p_arr.shape}")
            p, dp, _ = _lift_task(p_arr, dp, np.zeros(2))
        if not isinstance(compliance, str):
            raise TypeError("compliance: expected 'auto', 'rigid' or 'lumped'")
        A, B, C, D, inputs, model = self._core._linearize(p, dp, tau, output or "acceleration", compliance)
        return LinearModel((A, B) if output is None else (A, B, C, D), A, B, C, D, inputs, model)

    @_vocabulary
    def reactions(self, p, dp, ddp, *, threads=1, check=True, check_limits=True):
        """Every joint's reaction with the inverse dynamics' forces (the minimum-norm ones when
        redundant), as in `nocdyn inverse-dynamics --reactions`: base frame, the wrench of the
        joint's inboard body on its outboard body, the joint's effort and friction taken out
        (R: the force at the axis, m = 0; P: the force normal to the joint and the couple about
        the outboard body's c.o.m.).

        p, dp, ddp of shape (N, 3) ([x, y, theta], its rate and acceleration; float64, read in
        place whatever their memory order) give an array of shape (N, limbs, 3, 3): sample,
        limb, joint (file order: index j is limb j + 1, k joint k + 1), [fx, fy, m] [N, N, N m].
        One sample, shape (3,) each, gives (limbs, 3, 3). The GIL is released during the
        computation; threads as in inverse_dynamics. A sample out of reach or singular raises
        nocdyn.Error "sample K: <reason>" (the first such; failed rows are NaN); check=False
        returns instead. check_limits=True (the default, as `nocdyn inverse-dynamics
        --reactions`) raises nocdyn.Error at the first sample beyond a joint's range or
        velocity limit or an actuator's effort (checked by the full path at every sample);
        check_limits=False checks none. A two-DOF robot (motion: translation) takes p, dp, ddp of
        shape (2,) or (N, 2), columns x, y.
        """
        if self._core.task_dimension == 2:
            p, dp, ddp = _lift_task(p, dp, ddp)  # [x, y, 0]: theta is no coordinate
        threads = min(_integer(threads, "threads", 0, 2**63), _MAX_THREADS)
        p_arr = _floats(p, "p")
        single = p_arr.ndim == 1
        if single:
            p_arr = p_arr.reshape(1, -1)
            dp, ddp = _floats(dp, "dp").reshape(1, -1), _floats(ddp, "ddp").reshape(1, -1)
        if p_arr.ndim != 2:
            raise Error(f"p: expected shape (3,) or (N, 3), got {p_arr.shape}")
        n = p_arr.shape[0]
        if n == 0:
            raise ValueError("p: no samples (shape (0, 3)): give at least one pose")
        p_arr = _input(p_arr, "p", (None, 3), finite=False)
        dp_arr = _input(dp, "dp", (n, 3), finite=False)
        ddp_arr = _input(ddp, "ddp", (n, 3), finite=False)
        out = np.empty((n, self.limbs, 3, 3))
        self._core._reactions_batch(p_arr, dp_arr, ddp_arr, out.reshape(n, 9 * self.limbs), threads=threads,
                                    check=bool(check), check_limits=bool(check_limits), single=single)
        return out[0] if single else out

    @_vocabulary
    def regressor(self, p, dp, ddp):
        """The inverse-dynamics regressor Y, linear in the standard parameters: tau = Y pi.

        One sample: p, dp, ddp of shape (3,) ([x, y, theta], rate, acceleration) give Y of
        shape (n, P). A batch: (N, 3) float64
        arrays (read in place, any memory order) give the stacked regressor of shape (N * n, P),
        rows k * n .. k * n + n - 1 those of sample k (reshape(N, n, P) separates them). A
        sample out of reach or singular, or whose regressor is not finite, raises nocdyn.Error
        ("sample K: <reason>", K from 1). A two-DOF robot (motion: translation) takes p, dp, ddp of
        shape (2,) or (N, 2), columns x, y; its platform is a point mass at the tool point, so the
        columns platform.mc_x, platform.mc_y and platform.I_O (and the last R joints' friction) are 0."""
        if self._core.task_dimension == 2:
            p, dp, ddp = _lift_task(p, dp, ddp)  # [x, y, 0]: theta is no coordinate
        p_arr = _floats(p, "p")
        if p_arr.ndim == 1:
            Y = self._core._regressor_sample(p_arr, dp, ddp)
        elif p_arr.ndim == 2:
            n = p_arr.shape[0]
            Y = self._core._regressor_batch(_input(p_arr, "p", (None, 3), finite=False),
                                            _input(dp, "dp", (n, 3), finite=False),
                                            _input(ddp, "ddp", (n, 3), finite=False))
        else:
            raise Error(f"p: expected shape (3,) or (N, 3), got {p_arr.shape}")
        return Y
