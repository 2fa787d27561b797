!> Independent checks of what the regression covers: a held head in
!! static equilibrium against hand statics (the occipital-condyle force and
!! moment); the injury assessment of a whole synthetic run against a hand
!! computation (channels, CFC classes, units); the range-of-motion law.
module test_independent_checks
    use funit
    use hn_kinds, only: wp, zero, one, msglen, g_std, deg
    use hn_case, only: case_t
    use hn_deck, only: read_case
    use hn_run, only: run_state_t, run_result_t
    use hn_channels, only: channel_set_t, channels_define
    use hn_assessment, only: assessment_t, assess, criteria_input_t, criteria_input_allocate
    use hn_joint_limits, only: joint_range_t, range_moment, range_energy, range_warnings, range_margin
    implicit none

contains

    !@test
    subroutine test_held_head_condyle_loads_equal_hand_statics()
        ! case 6-1 before its impact (5 ms): T1 fixed, posture held, every
        ! muscle at its bracing activation. The head is at rest, so the neck
        ! carries its weight: Fz = -m g (compression), Fx = 0, and the moment
        ! of the weight about the condyles, 20 mm behind the mass centre:
        ! My = m g 0.020 (flexion positive), whatever the neck's elements do.
        type(case_t) :: cs
        type(run_result_t) :: res
        type(run_state_t) :: run
        type(channel_set_t) :: ch
        integer :: stat, lu
        character(len=msglen) :: msg
        real(wp) :: oc(4)
        real(wp), parameter :: m = 3.847_wp
        call read_case('input/case6-1.inp', 'input/case6-1.inp', cs, stat, msg)
#line 34 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(0, stat, msg, &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 34) )
  if (anyExceptions()) return
#line 35 "/work/main/test/unit/test_independent_checks.pf"
        cs%t_end = 0.002_wp
        call channels_define(cs, ch)
        open (newunit=lu, file='/dev/null', action='write')
        call run%execute(cs, lu, '', res, keep_samples=.true.)
        close (lu)
#line 40 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(0, res%exit_code, &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 40) )
  if (anyExceptions()) return
#line 41 "/work/main/test/unit/test_independent_checks.pf"
        oc = [res%samples(findloc(ch%name, 'OC_FX', dim=1), 1), res%samples(findloc(ch%name, 'OC_FZ', dim=1), 1), &
              res%samples(findloc(ch%name, 'OC_MX', dim=1), 1), res%samples(findloc(ch%name, 'OC_MY', dim=1), 1)]
#line 43 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(-m*g_std, oc(2), 1.0e-9_wp, 'OC Fz = -m g', &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 43) )
  if (anyExceptions()) return
#line 44 "/work/main/test/unit/test_independent_checks.pf"
#line 44 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(zero, oc(1), 1.0e-9_wp, 'OC Fx = 0', &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 44) )
  if (anyExceptions()) return
#line 45 "/work/main/test/unit/test_independent_checks.pf"
#line 45 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(m*g_std*0.020_wp, oc(4), 1.0e-9_wp, 'OC My = m g x 0.020 m', &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 45) )
  if (anyExceptions()) return
#line 46 "/work/main/test/unit/test_independent_checks.pf"
#line 46 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(zero, oc(3), 1.0e-9_wp, 'OC Mx = 0', &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 46) )
  if (anyExceptions()) return
#line 47 "/work/main/test/unit/test_independent_checks.pf"
    end subroutine test_held_head_condyle_loads_equal_hand_statics

    !@test
    subroutine test_assessment_of_a_synthetic_run()
        ! 501 samples every 0.1 ms from t0 = 0.01 s, every channel constant
        ! (a CFC filter started from rest passes a constant unchanged):
        ! head a = (30, 0, 40) g -> resultant 50 g; T1 31 g; OC Fx 500 N,
        ! Fz 1000 N, My 20 N m.
        type(criteria_input_t) :: hist
        type(assessment_t) :: a
        real(wp), parameter :: t0 = 0.01_wp, dt = 1.0e-4_wp
        call criteria_input_allocate(hist, 501)
        hist%head_ax = 30.0_wp; hist%head_ay = zero; hist%head_az = 40.0_wp
        hist%t1_ax = 31.0_wp
        hist%oc_fx = 500.0_wp; hist%oc_fz = 1000.0_wp; hist%oc_my = 20.0_wp
        call assess(t0, dt, hist, 501, a)
#line 63 "/work/main/test/unit/test_independent_checks.pf"
  call assertTrue(a%computed, &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 63) )
  if (anyExceptions()) return
#line 64 "/work/main/test/unit/test_independent_checks.pf"
        ! HIC = (t2 - t1) a^2.5 with a in g and t in s: 0.015 x 50^2.5 = 265.165; 0.036 x 50^2.5 = 636.396
#line 65 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(265.16504_wp, a%hic15, 1.0e-4_wp, &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 65) )
  if (anyExceptions()) return
#line 66 "/work/main/test/unit/test_independent_checks.pf"
#line 66 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(636.39610_wp, a%hic36, 1.0e-4_wp, &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 66) )
  if (anyExceptions()) return
#line 67 "/work/main/test/unit/test_independent_checks.pf"
#line 67 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(0.015_wp, a%hic15_t2 - a%hic15_t1, 1.0e-12_wp, 'the HIC15 window is 15 ms long', &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 67) )
  if (anyExceptions()) return
#line 68 "/work/main/test/unit/test_independent_checks.pf"
        ! Nij: tension with flexion, 1000/6806 + 20/310 = 0.14692918 + 0.06451613 = 0.21144531; others 0
#line 69 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(0.21144531_wp, a%nij_max(2), 1.0e-7_wp, 'NTF', &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 69) )
  if (anyExceptions()) return
#line 70 "/work/main/test/unit/test_independent_checks.pf"
#line 70 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(zero, a%nij_max(1), 'NTE', &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 70) )
  if (anyExceptions()) return
#line 71 "/work/main/test/unit/test_independent_checks.pf"
#line 71 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(zero, a%nij_max(3) + a%nij_max(4), 'NCE, NCF', &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 71) )
  if (anyExceptions()) return
#line 72 "/work/main/test/unit/test_independent_checks.pf"
#line 72 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(1000.0_wp, a%tension, 1.0e-9_wp, &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 72) )
  if (anyExceptions()) return
#line 73 "/work/main/test/unit/test_independent_checks.pf"
#line 73 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(500.0_wp, a%shear, 1.0e-9_wp, &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 73) )
  if (anyExceptions()) return
#line 74 "/work/main/test/unit/test_independent_checks.pf"
#line 74 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(20.0_wp, a%flexion, 1.0e-9_wp, &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 74) )
  if (anyExceptions()) return
#line 75 "/work/main/test/unit/test_independent_checks.pf"
        ! NIC = 0.2 a_rel + v_rel^2, a_rel = 1 g = 9.80665 m/s^2 (from g), v_rel = g t:
        ! largest at the end, t = 0.05 s: 1.961330 + 0.4903325^2 = 1.961330 + 0.2404260 = 2.2017560 m^2/s^2
#line 77 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(2.2017560_wp, a%nic_max, 1.0e-6_wp, &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 77) )
  if (anyExceptions()) return
#line 78 "/work/main/test/unit/test_independent_checks.pf"
#line 78 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(t0 + 0.05_wp, a%nic_time, 1.0e-12_wp, &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 78) )
  if (anyExceptions()) return
#line 79 "/work/main/test/unit/test_independent_checks.pf"
    end subroutine test_assessment_of_a_synthetic_run

    !@test
    subroutine test_assessment_refuses_coarse_sampling()
        type(criteria_input_t) :: hist
        type(assessment_t) :: a
        call criteria_input_allocate(hist, 100)
        hist%head_ax = one; hist%head_ay = one; hist%head_az = one; hist%t1_ax = one
        hist%oc_fx = one; hist%oc_fz = one; hist%oc_my = one
        call assess(zero, 2.0e-4_wp, hist, 100, a)
#line 89 "/work/main/test/unit/test_independent_checks.pf"
  call assertFalse(a%computed, 'CFC 1000 needs 0.1 ms sampling or finer', &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 89) )
  if (anyExceptions()) return
#line 90 "/work/main/test/unit/test_independent_checks.pf"
    end subroutine test_assessment_refuses_coarse_sampling

    !@test
    subroutine test_range_resistance_law()
        type(joint_range_t) :: r
        real(wp) :: h, x
        r%xmin = -10*deg; r%xmax = 10*deg; r%k = 50.0_wp; r%t0 = 3*deg
#line 97 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(zero, range_moment(r, 9.9_wp*deg), 'free inside the range', &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 97) )
  if (anyExceptions()) return
#line 98 "/work/main/test/unit/test_independent_checks.pf"
        ! 3 deg past the upper end: -K t0 (e - 1) = -50 x 0.05235988 x 1.71828183 = -4.4984513 N m
#line 99 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(-4.4984513_wp, range_moment(r, 13*deg), 1.0e-6_wp, &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 99) )
  if (anyExceptions()) return
#line 100 "/work/main/test/unit/test_independent_checks.pf"
#line 100 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(4.4984513_wp, range_moment(r, -13*deg), 1.0e-6_wp, 'symmetric below the lower end', &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 100) )
  if (anyExceptions()) return
#line 101 "/work/main/test/unit/test_independent_checks.pf"
        ! the moment is minus the derivative of the energy
        h = 1.0e-7_wp; x = 14*deg
#line 103 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(-(range_energy(r, x + h) - range_energy(r, x - h))/(2*h), range_moment(r, x), 1.0e-5_wp, &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 103) )
  if (anyExceptions()) return
#line 104 "/work/main/test/unit/test_independent_checks.pf"
    end subroutine test_range_resistance_law

    !@test
    subroutine test_range_warning_only_beyond_the_margin()
        type(joint_range_t) :: r(2)
        character(len=160), allocatable :: lines(:)
        r(1)%label = 'C5 RY'; r(1)%xmin = -7*deg; r(1)%xmax = 7*deg
        r(2)%label = 'C4 RY'; r(2)%xmin = -7*deg; r(2)%xmax = 7*deg
        lines = range_warnings(r, [range_margin*0.99_wp, range_margin*2], [0.1_wp, 0.12_wp], range_margin)
#line 113 "/work/main/test/unit/test_independent_checks.pf"
  call assertEqual(1, size(lines), &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 113) )
  if (anyExceptions()) return
#line 114 "/work/main/test/unit/test_independent_checks.pf"
#line 114 "/work/main/test/unit/test_independent_checks.pf"
  call assertTrue(index(lines(1), 'C4 RY') > 0, trim(lines(1)), &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 114) )
  if (anyExceptions()) return
#line 115 "/work/main/test/unit/test_independent_checks.pf"
#line 115 "/work/main/test/unit/test_independent_checks.pf"
  call assertTrue(index(lines(1), '120.0 ms') > 0, trim(lines(1)), &
 & location=SourceLocation( &
 & 'test_independent_checks.pf', &
 & 115) )
  if (anyExceptions()) return
#line 116 "/work/main/test/unit/test_independent_checks.pf"
    end subroutine test_range_warning_only_beyond_the_margin

end module test_independent_checks

module Wraptest_independent_checks
   use FUnit
   use test_independent_checks
   implicit none
   private

contains


end module Wraptest_independent_checks

function test_independent_checks_suite() result(suite)
   use FUnit
   use test_independent_checks
   use Wraptest_independent_checks
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_independent_checks_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_held_head_condyle_loads_equal_hand_statics', &
      test_held_head_condyle_loads_equal_hand_statics))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_assessment_of_a_synthetic_run', &
      test_assessment_of_a_synthetic_run))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_assessment_refuses_coarse_sampling', &
      test_assessment_refuses_coarse_sampling))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_range_resistance_law', &
      test_range_resistance_law))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_range_warning_only_beyond_the_margin', &
      test_range_warning_only_beyond_the_margin))
   call suite%addTest(t)


end function test_independent_checks_suite

