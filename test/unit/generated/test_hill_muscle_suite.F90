!> The Hill-type muscle (hn_muscle) against hand-computed forces -- isometric
!! at and off the optimal length, concentric, eccentric, the tension-only
!! clip -- and the activation history against its closed form at a step
!! and against a fine Runge-Kutta integration of da/dt = (u - a)/tau for a
!! ramp; the HILL and ACTIVATE cards of a deck.
module test_hill_muscle
    use funit
    use hn_kinds, only: wp, zero, one, msglen
    use hn_muscle, only: hill_t, activation_t, hill_force, hill_fv, activation_value, excitation_value
    use hn_line_elements, only: muscle_t, muscle_tension, muscle_hill
    implicit none

    real(wp), parameter :: tol = 1.0e-9_wp

contains

    function sample() result(h)
        type(hill_t) :: h
        h%f0 = 200.0_wp; h%lopt = 0.1_wp; h%vmax = 10.0_wp
    end function sample

    !@test
    subroutine test_isometric_at_optimal_length_is_f0()
        ! l = 1, v = 0, a = 1: fL = 1, fV = 1, fPE = 0 -> F = F0 = 200 N
#line 25 "/work/main/test/unit/test_hill_muscle.pf"
  call assertEqual(200.0_wp, hill_force(sample(), zero, zero, one), tol, &
 & location=SourceLocation( &
 & 'test_hill_muscle.pf', &
 & 25) )
  if (anyExceptions()) return
#line 26 "/work/main/test/unit/test_hill_muscle.pf"
    end subroutine test_isometric_at_optimal_length_is_f0

    !@test
    subroutine test_isometric_stretched_half_active()
        ! l = 1.2 (d = 0.02 m), a = 0.5: 200 [0.5 exp(-0.04/0.45) + (exp(4 0.2/0.6) - 1)/(exp(4) - 1)]
        ! = 200 [0.5 x 0.9149473 + 2.7936679/53.5981500] = 200 x 0.5095961 = 101.91922 N
#line 32 "/work/main/test/unit/test_hill_muscle.pf"
  call assertEqual(101.91922_wp, hill_force(sample(), 0.02_wp, zero, 0.5_wp), 1.0e-4_wp, &
 & location=SourceLocation( &
 & 'test_hill_muscle.pf', &
 & 32) )
  if (anyExceptions()) return
#line 33 "/work/main/test/unit/test_hill_muscle.pf"
    end subroutine test_isometric_stretched_half_active

    !@test
    subroutine test_isometric_shortened_no_passive_force()
        ! l = 0.8, a = 1: 200 exp(-0.04/0.45) = 182.98945 N; fPE = 0 below lopt
#line 38 "/work/main/test/unit/test_hill_muscle.pf"
  call assertEqual(182.98945_wp, hill_force(sample(), -0.02_wp, zero, one), 1.0e-4_wp, &
 & location=SourceLocation( &
 & 'test_hill_muscle.pf', &
 & 38) )
  if (anyExceptions()) return
#line 39 "/work/main/test/unit/test_hill_muscle.pf"
    end subroutine test_isometric_shortened_no_passive_force

    !@test
    subroutine test_concentric_quarter_vmax()
        ! shortening at vmax/4 = 0.25 m/s: fV = (1 - 0.25)/(1 + 0.25/0.25) = 0.375 -> 75 N
#line 44 "/work/main/test/unit/test_hill_muscle.pf"
  call assertEqual(75.0_wp, hill_force(sample(), zero, -0.25_wp, one), tol, &
 & location=SourceLocation( &
 & 'test_hill_muscle.pf', &
 & 44) )
  if (anyExceptions()) return
#line 45 "/work/main/test/unit/test_hill_muscle.pf"
    end subroutine test_concentric_quarter_vmax

    !@test
    subroutine test_concentric_beyond_vmax_is_zero()
#line 49 "/work/main/test/unit/test_hill_muscle.pf"
  call assertEqual(zero, hill_fv(sample(), -1.5_wp), tol, &
 & location=SourceLocation( &
 & 'test_hill_muscle.pf', &
 & 49) )
  if (anyExceptions()) return
#line 50 "/work/main/test/unit/test_hill_muscle.pf"
#line 50 "/work/main/test/unit/test_hill_muscle.pf"
  call assertEqual(zero, hill_force(sample(), zero, -1.0_wp, one), tol, &
 & location=SourceLocation( &
 & 'test_hill_muscle.pf', &
 & 50) )
  if (anyExceptions()) return
#line 51 "/work/main/test/unit/test_hill_muscle.pf"
    end subroutine test_concentric_beyond_vmax_is_zero

    !@test
    subroutine test_eccentric_halfway_to_flen()
        ! b = (1.4 - 1)/(2 (1 + 1/0.25)) = 0.04; at v = b: fV = 1.4 - 0.4/2 = 1.2
        ! lengthening at 0.04 x vmax lopt = 0.04 m/s -> 240 N
#line 57 "/work/main/test/unit/test_hill_muscle.pf"
  call assertEqual(240.0_wp, hill_force(sample(), zero, 0.04_wp, one), tol, &
 & location=SourceLocation( &
 & 'test_hill_muscle.pf', &
 & 57) )
  if (anyExceptions()) return
#line 58 "/work/main/test/unit/test_hill_muscle.pf"
    end subroutine test_eccentric_halfway_to_flen

    !@test
    subroutine test_eccentric_saturates_at_flen()
#line 62 "/work/main/test/unit/test_hill_muscle.pf"
  call assertEqual(1.4_wp, hill_fv(sample(), 1.0e9_wp), 1.0e-6_wp, &
 & location=SourceLocation( &
 & 'test_hill_muscle.pf', &
 & 62) )
  if (anyExceptions()) return
#line 63 "/work/main/test/unit/test_hill_muscle.pf"
    end subroutine test_eccentric_saturates_at_flen

    !@test
    subroutine test_damping_adds_along_the_line_and_muscle_never_pushes()
        type(muscle_t) :: m
        m = muscle_t(law=muscle_hill, length0=0.1_wp)
        m%hill = sample()
        m%hill%damping = 50.0_wp
        ! isometric passive-free, a = 0, lengthening 0.01 m/s: only the damper, 0.5 N
#line 72 "/work/main/test/unit/test_hill_muscle.pf"
  call assertEqual(0.5_wp, muscle_tension(m, 0.1_wp, 0.01_wp, zero), tol, &
 & location=SourceLocation( &
 & 'test_hill_muscle.pf', &
 & 72) )
  if (anyExceptions()) return
#line 73 "/work/main/test/unit/test_hill_muscle.pf"
        ! shortening with no activation: the damper would push; the muscle does not
#line 74 "/work/main/test/unit/test_hill_muscle.pf"
  call assertEqual(zero, muscle_tension(m, 0.1_wp, -0.2_wp, zero), tol, &
 & location=SourceLocation( &
 & 'test_hill_muscle.pf', &
 & 74) )
  if (anyExceptions()) return
#line 75 "/work/main/test/unit/test_hill_muscle.pf"
    end subroutine test_damping_adds_along_the_line_and_muscle_never_pushes

    function history(rise) result(ah)
        real(wp), intent(in) :: rise
        type(activation_t) :: ah
        ah%u0 = 0.05_wp; ah%u1 = one; ah%t_onset = 0.05_wp; ah%delay = 0.07_wp; ah%rise = rise
        ah%tau_act = 0.015_wp; ah%tau_deact = 0.05_wp
    end function history

    !@test
    subroutine test_activation_step_response()
        type(activation_t) :: ah
        ah = history(zero)
        ! bracing level until the reflex onset at 0.12 s
#line 89 "/work/main/test/unit/test_hill_muscle.pf"
  call assertEqual(0.05_wp, activation_value(ah, 0.10_wp), tol, &
 & location=SourceLocation( &
 & 'test_hill_muscle.pf', &
 & 89) )
  if (anyExceptions()) return
#line 90 "/work/main/test/unit/test_hill_muscle.pf"
#line 90 "/work/main/test/unit/test_hill_muscle.pf"
  call assertEqual(0.05_wp, activation_value(ah, 0.12_wp), tol, &
 & location=SourceLocation( &
 & 'test_hill_muscle.pf', &
 & 90) )
  if (anyExceptions()) return
#line 91 "/work/main/test/unit/test_hill_muscle.pf"
        ! one time constant after a step: 1 + (0.05 - 1) exp(-1) = 0.65051453
#line 92 "/work/main/test/unit/test_hill_muscle.pf"
  call assertEqual(0.65051453_wp, activation_value(ah, 0.135_wp), 1.0e-8_wp, &
 & location=SourceLocation( &
 & 'test_hill_muscle.pf', &
 & 92) )
  if (anyExceptions()) return
#line 93 "/work/main/test/unit/test_hill_muscle.pf"
        ! three time constants: 1 - 0.95 exp(-3) = 1 - 0.95 x 0.04978707 = 0.95270228
#line 94 "/work/main/test/unit/test_hill_muscle.pf"
  call assertEqual(0.95270228_wp, activation_value(ah, 0.165_wp), 1.0e-8_wp, &
 & location=SourceLocation( &
 & 'test_hill_muscle.pf', &
 & 94) )
  if (anyExceptions()) return
#line 95 "/work/main/test/unit/test_hill_muscle.pf"
    end subroutine test_activation_step_response

    !@test
    subroutine test_deactivation_uses_its_time_constant()
        type(activation_t) :: ah
        ah = history(zero)
        ah%u0 = 0.6_wp; ah%u1 = 0.1_wp
        ! 0.1 + 0.5 exp(-0.05/0.05) = 0.28393972
#line 103 "/work/main/test/unit/test_hill_muscle.pf"
  call assertEqual(0.28393972_wp, activation_value(ah, 0.17_wp), 1.0e-8_wp, &
 & location=SourceLocation( &
 & 'test_hill_muscle.pf', &
 & 103) )
  if (anyExceptions()) return
#line 104 "/work/main/test/unit/test_hill_muscle.pf"
    end subroutine test_deactivation_uses_its_time_constant

    !@test
    subroutine test_activation_ramp_matches_runge_kutta()
        type(activation_t) :: ah
        real(wp) :: a, t, h, k1, k2, k3, k4, worst
        integer :: n
        ah = history(0.02_wp)
        ! classical RK4 on da/dt = (u(t) - a)/tau_act from a = u0 at t = 0, h = 1 us
        a = ah%u0; t = zero; h = 1.0e-6_wp; worst = zero
        do n = 1, 250000
            k1 = (excitation_value(ah, t) - a)/ah%tau_act
            k2 = (excitation_value(ah, t + h/2) - (a + h/2*k1))/ah%tau_act
            k3 = (excitation_value(ah, t + h/2) - (a + h/2*k2))/ah%tau_act
            k4 = (excitation_value(ah, t + h) - (a + h*k3))/ah%tau_act
            a = a + h/6*(k1 + 2*k2 + 2*k3 + k4)
            t = n*h
            worst = max(worst, abs(a - activation_value(ah, t)))
        end do
#line 123 "/work/main/test/unit/test_hill_muscle.pf"
  call assertLessThan(worst, 1.0e-9_wp, 'closed form = RK4 over 0-0.25 s', &
 & location=SourceLocation( &
 & 'test_hill_muscle.pf', &
 & 123) )
  if (anyExceptions()) return
#line 124 "/work/main/test/unit/test_hill_muscle.pf"
#line 124 "/work/main/test/unit/test_hill_muscle.pf"
  call assertLessThan(activation_value(ah, 0.14_wp), excitation_value(ah, 0.14_wp), 'activation lags the ramp', &
 & location=SourceLocation( &
 & 'test_hill_muscle.pf', &
 & 124) )
  if (anyExceptions()) return
#line 125 "/work/main/test/unit/test_hill_muscle.pf"
    end subroutine test_activation_ramp_matches_runge_kutta

end module test_hill_muscle

module Wraptest_hill_muscle
   use FUnit
   use test_hill_muscle
   implicit none
   private

contains


end module Wraptest_hill_muscle

function test_hill_muscle_suite() result(suite)
   use FUnit
   use test_hill_muscle
   use Wraptest_hill_muscle
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_hill_muscle_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_isometric_at_optimal_length_is_f0', &
      test_isometric_at_optimal_length_is_f0))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_isometric_stretched_half_active', &
      test_isometric_stretched_half_active))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_isometric_shortened_no_passive_force', &
      test_isometric_shortened_no_passive_force))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_concentric_quarter_vmax', &
      test_concentric_quarter_vmax))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_concentric_beyond_vmax_is_zero', &
      test_concentric_beyond_vmax_is_zero))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_eccentric_halfway_to_flen', &
      test_eccentric_halfway_to_flen))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_eccentric_saturates_at_flen', &
      test_eccentric_saturates_at_flen))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_damping_adds_along_the_line_and_muscle_never_pushes', &
      test_damping_adds_along_the_line_and_muscle_never_pushes))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_activation_step_response', &
      test_activation_step_response))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_deactivation_uses_its_time_constant', &
      test_deactivation_uses_its_time_constant))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_activation_ramp_matches_runge_kutta', &
      test_activation_ramp_matches_runge_kutta))
   call suite%addTest(t)


end function test_hill_muscle_suite

