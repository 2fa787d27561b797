!> Postural feedback of muscle activation (beyond the 1978 paper): a
!! sampled-data controller that adds to an activation history (ACTIVATE
!! card) the excitation its sensor asks for, the way the closed-loop neck
!! muscles of active human body models act on the head's rotation relative
!! to the lab (vestibular feedback; Östh et al. 2012, Putra et al. 2021:
!! PID control of the head's angle; docs/deck-format.md, FEEDBACK).
!!
!! Sensor: the rotation of a body relative to its orientation at the start
!! of the run, as the component along a lab axis e of the rotation vector
!! of S(t) S(t0)^T (S the body-to-lab matrix), theta, and the component of
!! the body's angular velocity along e, omega (rad, rad/s).
!!
!! Controller: sampled every dt from the start t0 (t_k = t0 + k dt); at
!! t_k the excitation is set from the sensor a delay tau earlier,
!!   u_k = min(1, max(0, kp theta(t_k - tau) + kd omega(t_k - tau))),
!! theta and omega between samples linear in time, before t0 their start
!! values (a delay that is not a multiple of dt interpolates the samples);
!! u_k is held until t_{k+1} (zero before the first sample). With an
!! integral gain ki (a rotation loop's, the I of the PID controllers
!! cited above) the sum I_k = I_{k-1} + dt theta(t_k - tau) (I_0 = dt
!! theta at the first sample) adds ki I_k inside the clip, ki I_k itself
!! kept within [-1, 1] (no wind-up beyond a full excitation): a load held
!! at rest, which kp alone answers with a lasting offset, is answered
!! with the offset going to zero. The loop
!! gives an excitation only: it is added to its history's, and the
!! history's activation, a state of the equations of motion, follows the
!! sum (hn_muscle_family), so the excitation falls back to the history's
!! own as soon as the sensor is back.
!!
!! A stretch loop (SPINDLE card) is the same controller on one muscle, its
!! sensor the muscle's own stretch (the muscle-spindle feedback of
!! multisegment neuromuscular neck models, Happee et al. 2017, S18 of
!! reference/parameters.md):
!! theta = (L(t) - L(t0))/lopt and omega = dL/dt / lopt, L the muscle's
!! path length, lopt its optimal fibre length; its excitation drives an
!! activation state of that muscle alone (`state`), added to its
!! history's. Its gains may rise with the muscle's activation
!! (alpha-gamma co-activation, the automatic gain compensation of the
!! stretch reflex): at t_k both are multiplied by 1 + g a_b(t_k), a_b the
!! muscle's activation then without the loop's own (its history's and the
!! history's rotation loops'), g >= 0 (g = 0: fixed gains),
!!   u_k = min(1, max(0, (1 + g a_b(t_k)) (kp theta(t_k - tau) + kd omega(t_k - tau)))),
!! plus ki I_k inside the clip with an integral gain (SPINDLE F7), as above.
module hn_feedback
    use hn_kinds, only: wp, zero, one
    use hn_rotation, only: rotation_vector
    implicit none
    private

    public :: feedback_t, feedback_excitation, feedback_sample, stretch_sample, feedback_due, &
              feedback_times, sensor_angle

    !> One feedback loop: sensor, gains, delay, sampling, and its held state.
    type :: feedback_t
        integer :: history = 0           !! the activation history it adds to (ACTIVATE card number)
        integer :: body = 0              !! the sensor body (tree number)
        integer :: axis = 2              !! the lab axis of the sensor (1 x, 2 y, 3 z)
        integer :: muscle = 0            !! a stretch loop's muscle (0: a rotation loop, on every muscle of the history)
        real(wp) :: lopt = one           !! a stretch loop's optimal fibre length, the stretch's unit [m]
        real(wp) :: kp = zero            !! gain on the rotation [1/rad]
        real(wp) :: kd = zero            !! gain on the angular velocity [s/rad]
        real(wp) :: ki = zero            !! gain on the rotation's time integral [1/(rad s)]
        real(wp) :: gain_act = zero      !! a stretch loop's gain rise per unit of its muscle's activation g [-]
        real(wp) :: delay = zero         !! sensing and neural delay tau [s]
        real(wp) :: dt = 1.0e-3_wp       !! sample interval [s]
        real(wp) :: tau_act = 0.015_wp   !! activation time constant [s] (its history's)
        real(wp) :: tau_deact = 0.05_wp  !! deactivation time constant [s] (its history's)
        integer :: state = 0             !! a stretch loop's activation state (its family's numbering)
        ! the state of a run: samples and the hold
        integer :: n = 0                          !! samples so far (0: the run has not started it)
        real(wp) :: t0 = zero                     !! time of the first sample [s]
        real(wp) :: s0(3, 3) = zero               !! the sensor body's orientation then
        real(wp) :: l0 = zero                     !! a stretch loop's muscle length then [m]
        real(wp), allocatable :: theta(:)         !! (n) sampled rotation [rad]
        real(wp), allocatable :: omega(:)         !! (n) sampled angular velocity [rad/s]
        real(wp) :: tk = zero                     !! the last sample time [s]
        real(wp) :: uk = zero                     !! the excitation held since
        real(wp) :: integral = zero               !! the delayed rotation summed over the samples, I_k [rad s]
    end type feedback_t

contains

    !> The excitation kp theta + kd omega at t - tau, times the gains'
    !! scale (default 1), plus ki times the loop's integral, clipped to
    !! [0, 1], from the samples so far.
    pure real(wp) function feedback_excitation(fb, t, scale) result(u)
        type(feedback_t), intent(in) :: fb         !! the loop, at least one sample taken
        real(wp), intent(in) :: t                  !! the sample time [s]
        real(wp), intent(in), optional :: scale    !! the gains' factor, 1 + g a_b (default 1)
        real(wp) :: theta, omega
        call delayed_sensor(fb, t, theta, omega)
        u = fb%kp*theta + fb%kd*omega
        if (present(scale)) u = scale*u
        u = min(one, max(zero, u + fb%ki*fb%integral))
    end function feedback_excitation

    !> The sensor's rotation and rate at t - tau, linear between the
    !! samples so far, the first sample's before it.
    pure subroutine delayed_sensor(fb, t, theta, omega)
        type(feedback_t), intent(in) :: fb    !! the loop, at least one sample taken
        real(wp), intent(in) :: t             !! the time [s]
        real(wp), intent(out) :: theta        !! the rotation at t - tau
        real(wp), intent(out) :: omega        !! its rate at t - tau
        real(wp) :: p, w
        integer :: i
        p = (t - fb%delay - fb%t0)/fb%dt
        if (p <= zero) then
            i = 1; w = zero
        else
            i = min(int(p) + 1, fb%n)
            w = merge(p - (i - 1), zero, i < fb%n)
        end if
        if (i < fb%n) then
            theta = (one - w)*fb%theta(i) + w*fb%theta(i + 1)
            omega = (one - w)*fb%omega(i) + w*fb%omega(i + 1)
        else
            theta = fb%theta(fb%n)
            omega = fb%omega(fb%n)
        end if
    end subroutine delayed_sensor

    !> The sensor's rotation about lab axis `axis` from orientation s0 to s:
    !! that component of the rotation vector of s s0^T [rad].
    pure real(wp) function sensor_angle(s, s0, axis) result(theta)
        real(wp), intent(in) :: s(3, 3)    !! body-to-lab matrix now
        real(wp), intent(in) :: s0(3, 3)   !! the same at the start
        integer, intent(in) :: axis        !! 1, 2 or 3
        real(wp) :: v(3)
        v = rotation_vector(matmul(s, transpose(s0)))
        theta = v(axis)
    end function sensor_angle

    !> True when t is the loop's next sample time (within tol), or it has none yet.
    elemental logical function feedback_due(fb, t, tol) result(due)
        type(feedback_t), intent(in) :: fb   !! the loop
        real(wp), intent(in) :: t            !! time reached [s]
        real(wp), intent(in) :: tol          !! time tolerance [s]
        due = fb%n == 0
        if (.not. due) due = abs(t - (fb%t0 + fb%n*fb%dt)) <= tol
    end function feedback_due

    !> Take a sample at t of a rotation loop: the sensor body's orientation
    !! s and angular velocity w (lab frame); a new hold starts with the
    !! excitation of feedback_excitation. The first sample starts the run's
    !! state (the start orientation).
    pure subroutine feedback_sample(fb, t, s, w)
        type(feedback_t), intent(inout) :: fb   !! the loop; out: the sample and the new hold
        real(wp), intent(in) :: t               !! the sample time [s]
        real(wp), intent(in) :: s(3, 3)         !! the sensor body's body-to-lab matrix
        real(wp), intent(in) :: w(3)            !! its angular velocity in the lab [rad/s]
        if (fb%n == 0) fb%s0 = s
        call record_sample(fb, t, sensor_angle(s, fb%s0, fb%axis), w(fb%axis), one)
    end subroutine feedback_sample

    !> Take a sample at t of a stretch loop: its muscle's path length and
    !! lengthening rate; the stretch from the first sample's length and the
    !! rate, both over lopt, start a new hold as in feedback_sample, the
    !! gains times 1 + g a_b (a_b the muscle's activation without the loop's).
    pure subroutine stretch_sample(fb, t, length, rate, a_b)
        type(feedback_t), intent(inout) :: fb   !! the loop; out: the sample and the new hold
        real(wp), intent(in) :: t               !! the sample time [s]
        real(wp), intent(in) :: length          !! the muscle's path length [m]
        real(wp), intent(in) :: rate            !! its rate of lengthening [m/s]
        real(wp), intent(in) :: a_b             !! the muscle's activation at t without the loop's own
        if (fb%n == 0) fb%l0 = length
        call record_sample(fb, t, (length - fb%l0)/fb%lopt, rate/fb%lopt, one + fb%gain_act*a_b)
    end subroutine stretch_sample

    !> Append the sensor's value theta and rate omega at t and start the
    !! hold there, the gains times scale (the first sample starts the
    !! run's state).
    pure subroutine record_sample(fb, t, theta, omega, scale)
        type(feedback_t), intent(inout) :: fb   !! the loop; out: the sample and the new hold
        real(wp), intent(in) :: t               !! the sample time [s]
        real(wp), intent(in) :: theta           !! the sensor's value
        real(wp), intent(in) :: omega           !! its rate
        real(wp), intent(in) :: scale           !! the gains' factor
        real(wp), allocatable :: grown(:)
        real(wp) :: delayed, rate
        if (fb%n == 0) then
            fb%t0 = t
            if (allocated(fb%theta)) deallocate (fb%theta)
            if (allocated(fb%omega)) deallocate (fb%omega)
            allocate (fb%theta(64), fb%omega(64))
        end if
        if (fb%n == size(fb%theta)) then      ! room doubled: appending one by one is quadratic
            allocate (grown(2*fb%n)); grown(1:fb%n) = fb%theta; call move_alloc(grown, fb%theta)
            allocate (grown(2*fb%n)); grown(1:fb%n) = fb%omega; call move_alloc(grown, fb%omega)
        end if
        fb%n = fb%n + 1
        fb%theta(fb%n) = theta
        fb%omega(fb%n) = omega
        fb%tk = t
        if (fb%n == 1) fb%integral = zero
        if (fb%ki /= zero) then
            call delayed_sensor(fb, t, delayed, rate)
            fb%integral = fb%integral + fb%dt*delayed
            fb%integral = min(one, max(-one, fb%ki*fb%integral))/fb%ki
        end if
        fb%uk = feedback_excitation(fb, t, scale)
    end subroutine record_sample

    !> The loop's sample times t0 + k dt in [t0, t1] (t1 included within tol).
    pure function feedback_times(fb, t0, t1, tol) result(tk)
        type(feedback_t), intent(in) :: fb   !! the loop
        real(wp), intent(in) :: t0           !! start of the run [s]
        real(wp), intent(in) :: t1           !! its end [s]
        real(wp), intent(in) :: tol          !! time tolerance [s]
        real(wp), allocatable :: tk(:)
        integer :: k, n
        n = max(0, floor((t1 - t0 + tol)/fb%dt))
        tk = [(t0 + k*fb%dt, k=0, n)]
    end function feedback_times

end module hn_feedback
