!> Hill-type muscle law and first-order activation dynamics (beyond the
!! 1978 paper, whose muscle is the passive element of eq 11).
!!
!! Force along the muscle line (tension positive, never pushing):
!!   F = max(0, F0 [a fL(l) fV(v) + fPE(l)] + c L')
!! with the normalised fibre length l = ln + (L - L0)/lopt, ln the fibres'
!! length over their optimal length lopt in the neutral posture (L = L0;
!! default 1: at lopt), rigid tendon, no pennation, and the normalised
!! lengthening rate v = L'/(vmax lopt):
!!   fL(l)  = exp(-(l - 1)^2/gamma)                       (Thelen 2003)
!!   fPE(l) = (exp(kpe (l - 1)/eps0) - 1)/(exp(kpe) - 1), l > 1; 0 otherwise
!!   fV(v)  = (1 + v)/(1 - v/af) for -1 <= v <= 0 (Hill's hyperbola),
!!            0 for v < -1, and flen - (flen - 1) b/(b + v) for v > 0
!!            with b = (flen - 1)/(2 (1 + 1/af)): the eccentric branch starts
!!            with twice the concentric slope and saturates at flen.
!! c L' is the damping element acting along the line. The parallel elastic
!! element fPE acts from its slack length, the optimal fibre length (l = 1,
!! Thelen 2003; OpenSim's Millard2012 muscle: passive-fibre strain 0 at zero
!! force): a muscle whose neutral posture stretches its fibres past lopt
!! (ln > 1) carries a passive tension there.
!!
!! Around the neutral posture the active force changes with the length as
!! F0 a fL'(ln)/lopt, fL'(l) = -2 (l - 1)/gamma fL(l): positive (a stretched
!! active muscle gains force) on the ascending limb, ln < 1, where most neck
!! muscles sit in the neutral posture (Vasavada et al. 1998's model lineage:
!! reference/model_parameters.csv), zero at ln = 1, negative past the plateau.
!!
!! Short-range (intrinsic) stiffness of the active fibres, beyond Hill's
!! law: the attached cross-bridges make an active muscle resist a small
!! stretch with a stiffness proportional to its force, k = q F / L
!! (Bergmark 1989; Cholewicki & McGill 1996), F the active isometric force
!! F0 a fL(l), L the muscle's rest length L0. It holds over a short range
!! only, a stretch of about r lopt, beyond which the bridges detach and the
!! force-length and force-velocity relations take over:
!!   F_srs = k r lopt tanh(d/(r lopt)),   d = L - L0
!! (slope k at the rest length, bounded by k r lopt). It adds the stiffness
!! the force-length curve lacks at lopt (its slope is zero there, negative
!! beyond), which an activated neck needs to stand: without it the
!! compression of the bracing muscles buckles the column.
!!
!! Activation: excitation u(t) = u0 until t1 = onset + delay, then a ramp to
!! u1 over the rise time, then u1; da/dt = (u - a)/tau with a(t <= t1) = u0.
!! The history is monotone, so one time constant holds throughout (tau_act
!! when u1 >= u0, tau_deact otherwise) and a(t) is solved in closed form:
!! no state is added to the mechanical ODE.
module hn_muscle
    use hn_kinds, only: wp, zero, one
    implicit none
    private

    public :: hill_t, activation_t, hill_force, hill_fl, hill_fv, hill_fpe, activation_value, excitation_value

    !> Parameters of one Hill-type muscle.
    type :: hill_t
        real(wp) :: f0 = zero        !! maximum isometric force PCSA x sigma_max [N]
        real(wp) :: lopt = 0.1_wp    !! optimal fibre length [m]
        real(wp) :: vmax = 10.0_wp   !! maximum shortening velocity [lopt/s]
        real(wp) :: damping = zero   !! damping along the line [N s/m]
        real(wp) :: gamma = 0.45_wp  !! width of the force-length curve
        real(wp) :: kpe = 4.0_wp     !! shape of the passive curve
        real(wp) :: eps0 = 0.6_wp    !! passive strain at F0
        real(wp) :: af = 0.25_wp     !! Hill's a/F0
        real(wp) :: flen = 1.4_wp    !! eccentric force limit [F0]
        real(wp) :: srs_q = zero     !! short-range stiffness k = q F / L0 (0: none)
        real(wp) :: srs_range = 0.01_wp   !! stretch over which it holds [lopt]
        real(wp) :: l0 = zero        !! rest length L0 of the muscle [m] (set with the neutral lengths)
        real(wp) :: ln = one         !! fibre length / lopt at the rest length L0 (the neutral posture)
    end type hill_t

    !> An activation history: bracing level, reflex onset, rise, time constant.
    type :: activation_t
        character(len=10) :: name = ''
        real(wp) :: u0 = zero        !! pre-activation (bracing) level
        real(wp) :: u1 = zero        !! reflex level
        real(wp) :: t_onset = zero   !! sled pulse onset [s]
        real(wp) :: delay = zero     !! reflex delay after the onset [s]
        real(wp) :: rise = zero      !! rise time of the excitation [s]
        real(wp) :: tau_act = 0.015_wp    !! activation time constant [s]
        real(wp) :: tau_deact = 0.05_wp   !! deactivation time constant [s]
        real(wp) :: srs_q = zero          !! short-range stiffness q of the muscles it drives (hill_t)
        real(wp) :: srs_range = 0.01_wp   !! its range [lopt]
    end type activation_t

contains

    !> Active force-length relation fL(l) at normalised fibre length l.
    elemental real(wp) function hill_fl(h, l) result(f)
        type(hill_t), intent(in) :: h   !! the muscle
        real(wp), intent(in) :: l       !! fibre length / optimal length
        f = exp(-(l - one)**2/h%gamma)
    end function hill_fl

    !> Passive force-length relation fPE(l) (zero at and below lopt).
    elemental real(wp) function hill_fpe(h, l) result(f)
        type(hill_t), intent(in) :: h   !! the muscle
        real(wp), intent(in) :: l       !! fibre length / optimal length
        if (l > one) then
            f = (exp(h%kpe*(l - one)/h%eps0) - one)/(exp(h%kpe) - one)
        else
            f = zero
        end if
    end function hill_fpe

    !> Force-velocity relation fV(v) at normalised lengthening rate v.
    elemental real(wp) function hill_fv(h, v) result(f)
        type(hill_t), intent(in) :: h   !! the muscle
        real(wp), intent(in) :: v       !! lengthening rate / (vmax lopt); negative shortening
        real(wp) :: b
        if (v <= -one) then
            f = zero
        else if (v <= zero) then
            f = (one + v)/(one - v/h%af)
        else
            b = (h%flen - one)/(2*(one + one/h%af))
            f = h%flen - (h%flen - one)*b/(b + v)
        end if
    end function hill_fv

    !> Unclipped Hill force F0 [a fL fV + fPE] + c L' + F_srs at stretch
    !! d = L - L0, lengthening rate L' and activation a (negative only when
    !! the damper pushes harder than the fibres pull).
    elemental real(wp) function hill_force(h, d, rate, act) result(f)
        type(hill_t), intent(in) :: h      !! the muscle
        real(wp), intent(in) :: d          !! stretch from the neutral length [m]
        real(wp), intent(in) :: rate       !! lengthening rate [m/s]
        real(wp), intent(in) :: act        !! activation in [0, 1]
        real(wp) :: l, fa, r
        l = h%ln + d/h%lopt
        fa = h%f0*act*hill_fl(h, l)
        f = fa*hill_fv(h, rate/(h%vmax*h%lopt)) + h%f0*hill_fpe(h, l) + h%damping*rate
        if (h%srs_q > zero .and. h%l0 > zero) then
            r = h%srs_range*h%lopt
            f = f + h%srs_q*fa/h%l0*r*tanh(d/r)
        end if
    end function hill_force

    !> Excitation u(t): u0, a linear ramp to u1 over the rise time from
    !! onset + delay, then u1.
    elemental real(wp) function excitation_value(ah, t) result(u)
        type(activation_t), intent(in) :: ah   !! the history
        real(wp), intent(in) :: t              !! time [s]
        real(wp) :: t1
        t1 = ah%t_onset + ah%delay
        if (t <= t1) then
            u = ah%u0
        else if (t >= t1 + ah%rise) then
            u = ah%u1
        else
            u = ah%u0 + (ah%u1 - ah%u0)*(t - t1)/ah%rise
        end if
    end function excitation_value

    !> Activation a(t), the exact solution of da/dt = (u - a)/tau for the
    !! excitation of `excitation_value` with a = u0 up to the reflex onset.
    elemental real(wp) function activation_value(ah, t) result(a)
        type(activation_t), intent(in) :: ah   !! the history
        real(wp), intent(in) :: t              !! time [s]
        real(wp) :: t1, tau, s, a2, tr
        t1 = ah%t_onset + ah%delay
        tau = merge(ah%tau_act, ah%tau_deact, ah%u1 >= ah%u0)
        if (t <= t1) then
            a = ah%u0
            return
        end if
        if (ah%rise > zero) then
            s = (ah%u1 - ah%u0)/ah%rise
            tr = min(t - t1, ah%rise)
            ! a = u - s tau (1 - exp(-tr/tau)) while the ramp lasts
            a2 = ah%u0 + s*tr - s*tau*(one - exp(-tr/tau))
            if (t - t1 <= ah%rise) then
                a = a2
                return
            end if
        else
            a2 = ah%u0
        end if
        a = ah%u1 + (a2 - ah%u1)*exp(-(t - t1 - ah%rise)/tau)
    end function activation_value

end module hn_muscle
