!> The recursive forms of Kane's equations against the paper's: a_ij by
!! the composite-rigid-body recursion against eq 17 (partial velocities),
!! f_i by the recursive Newton-Euler form against eq 18, the recursive
!! velocity-dependent accelerations against sum (dv_pq/dt) xdot_q, and the
!! articulated-body solve and the CHOLESKY path against Gaussian
!! elimination of eq 17/18 (the independent reference), on random trees of
!! 9-72 bodies with locked and prescribed coordinates.
module test_recursive_dynamics
    use funit
    use hn_kinds, only: wp, zero, one, msglen
    use hn_random, only: rng_t
    use hn_rotation, only: axis_angle_matrix
    use hn_tree, only: body_tree_t, tree_allocate, tree_build
    use hn_kinematics, only: kinematics_t, kinematics_allocate, partial_velocities, body_kinematics
    use hn_loads, only: body_loads_t, loads_allocate
    use hn_kane, only: a_ij, f_i
    use hn_recursive, only: composite_rigid_body, f_recursive, inertia_times
    use hn_model, only: model_t, model_init
    use hn_motion, only: motion_harmonic
    use hn_dynamics, only: dyn_workspace_t, dynamics_setup, dynamics_evaluate
    use hn_linsolve, only: solver_gauss, solver_cholesky, solver_articulated
    implicit none

    integer, parameter :: sizes(4) = [9, 18, 36, 72]

contains

    !> A random tree of nb bodies: each body hangs one to three bodies below
    !! the previous (deep chains with branches), random masses, inertias
    !! and offsets, about one coordinate in eight locked at a random value.
    subroutine random_tree(tree, nb, rng)
        type(body_tree_t), intent(out) :: tree
        integer, intent(in) :: nb
        type(rng_t), intent(inout) :: rng
        integer :: k, m, stat, i
        real(wp) :: p(3), r(3, 3)
        character(len=msglen) :: msg
        call tree_allocate(tree, nb)
        do k = 1, nb
            tree%parent(k) = merge(0, max(1, k - 1 - int(3*rng%uniform(zero, one))), k == 1)
            tree%mass(k) = rng%uniform(0.3_wp, 4.0_wp)
            p = [rng%uniform(0.5_wp, 1.0_wp), rng%uniform(0.5_wp, 1.0_wp), zero]
            p(3) = rng%uniform(abs(p(1) - p(2)) + 0.1_wp, p(1) + p(2) - 0.05_wp)
            r = axis_angle_matrix([rng%uniform(-2.0_wp, 2.0_wp), rng%uniform(-2.0_wp, 2.0_wp), &
                                   rng%uniform(-2.0_wp, 2.0_wp)])
            tree%inertia(:, :, k) = zero
            do i = 1, 3
                tree%inertia(i, i, k) = 0.01_wp*p(i)
            end do
            tree%inertia(:, :, k) = matmul(r, matmul(tree%inertia(:, :, k), transpose(r)))
            tree%inertia(:, :, k) = 0.5_wp*(tree%inertia(:, :, k) + transpose(tree%inertia(:, :, k)))
            tree%joint_parent(:, k) = [rng%uniform(-0.05_wp, 0.05_wp), rng%uniform(-0.05_wp, 0.05_wp), &
                                       rng%uniform(0.0_wp, 0.08_wp)]
            tree%joint_child(:, k) = [rng%uniform(-0.05_wp, 0.05_wp), rng%uniform(-0.05_wp, 0.05_wp), &
                                      rng%uniform(-0.08_wp, 0.0_wp)]
            do m = 1, 6
                if (rng%uniform(zero, one) < 0.125_wp) then
                    tree%active(m, k) = .false.
                    tree%q_ref(m, k) = rng%uniform(-0.3_wp, 0.3_wp)
                end if
            end do
        end do
        call tree_build(tree, stat, msg)
#line 64 "/work/main/test/unit/test_recursive_dynamics.pf"
  call assertEqual(0, stat, trim(msg), &
 & location=SourceLocation( &
 & 'test_recursive_dynamics.pf', &
 & 64) )
  if (anyExceptions()) return
#line 65 "/work/main/test/unit/test_recursive_dynamics.pf"
    end subroutine random_tree

    !> Random coordinates (angles well inside the Bryant range) and rates.
    subroutine random_state(rng, n, x, xd)
        type(rng_t), intent(inout) :: rng
        integer, intent(in) :: n
        real(wp), intent(out) :: x(n), xd(n)
        integer :: j
        do j = 1, n
            x(j) = rng%uniform(-0.6_wp, 0.6_wp)
            xd(j) = rng%uniform(-3.0_wp, 3.0_wp)
        end do
    end subroutine random_state

    !@test
    subroutine test_composite_rigid_body_equals_eq17()
        type(rng_t) :: rng
        type(body_tree_t) :: tree
        type(kinematics_t) :: kin
        real(wp), allocatable :: x(:), xd(:), a17(:, :), ac(:, :)
        integer :: k
        call rng%seed(12)
        do k = 1, size(sizes)
            call random_tree(tree, sizes(k), rng)
            allocate (x(tree%ndof), xd(tree%ndof), a17(tree%ndof, tree%ndof), ac(tree%ndof, tree%ndof))
            call random_state(rng, tree%ndof, x, xd)
            call kinematics_allocate(tree, kin)
            call partial_velocities(tree, x, xd, kin)
            call a_ij(tree, kin, a17)
            call body_kinematics(tree, x, xd, kin)
            call composite_rigid_body(tree, kin, ac)
#line 96 "/work/main/test/unit/test_recursive_dynamics.pf"
  call assertTrue(maxval(abs(ac - a17)) <= 1.0e-12_wp*maxval(abs(a17)), 'a_ij by CRBA = eq 17 to 1e-12', &
 & location=SourceLocation( &
 & 'test_recursive_dynamics.pf', &
 & 96) )
  if (anyExceptions()) return
#line 97 "/work/main/test/unit/test_recursive_dynamics.pf"
#line 97 "/work/main/test/unit/test_recursive_dynamics.pf"
  call assertTrue(all(ac == transpose(ac)), 'CRBA a_ij exactly symmetric', &
 & location=SourceLocation( &
 & 'test_recursive_dynamics.pf', &
 & 97) )
  if (anyExceptions()) return
#line 98 "/work/main/test/unit/test_recursive_dynamics.pf"
            deallocate (x, xd, a17, ac)
        end do
    end subroutine test_composite_rigid_body_equals_eq17

    !@test
    subroutine test_recursive_f_equals_eq18()
        type(rng_t) :: rng
        type(body_tree_t) :: tree
        type(kinematics_t) :: kin
        type(body_loads_t) :: loads
        real(wp), allocatable :: x(:), xd(:), f18(:), fr(:), a0(:, :), al0(:, :)
        integer :: k, p, j, jj
        call rng%seed(34)
        do k = 1, size(sizes)
            call random_tree(tree, sizes(k), rng)
            allocate (x(tree%ndof), xd(tree%ndof), f18(tree%ndof), fr(tree%ndof))
            call random_state(rng, tree%ndof, x, xd)
            call kinematics_allocate(tree, kin)
            call loads_allocate(loads, tree%nbody, tree%ndof)
            do p = 1, tree%nbody
                loads%force(:, p) = [rng%uniform(-50.0_wp, 50.0_wp), rng%uniform(-50.0_wp, 50.0_wp), &
                                     rng%uniform(-50.0_wp, 50.0_wp)]
                loads%moment(:, p) = [rng%uniform(-5.0_wp, 5.0_wp), rng%uniform(-5.0_wp, 5.0_wp), &
                                      rng%uniform(-5.0_wp, 5.0_wp)]
            end do
            do j = 1, tree%ndof
                loads%q(j) = rng%uniform(-2.0_wp, 2.0_wp)
            end do
            call partial_velocities(tree, x, xd, kin)
            ! the paper's velocity-dependent accelerations from the derivatives of the partials
            a0 = kin%a0
            al0 = kin%alpha0
            do p = 1, tree%nbody
                a0(:, p) = zero; al0(:, p) = zero
                do jj = 1, tree%chain_len(p)
                    j = tree%chain(jj, p)
                    a0(:, p) = a0(:, p) + kin%vd(:, j, p)*xd(j)
                    al0(:, p) = al0(:, p) + kin%wd(:, j, p)*xd(j)
                end do
            end do
#line 138 "/work/main/test/unit/test_recursive_dynamics.pf"
  call assertTrue(maxval(abs(kin%a0 - a0)) <= 1.0e-12_wp*maxval(abs(a0)), 'recursive a0 = sum dv_pq/dt xdot_q', &
 & location=SourceLocation( &
 & 'test_recursive_dynamics.pf', &
 & 138) )
  if (anyExceptions()) return
#line 139 "/work/main/test/unit/test_recursive_dynamics.pf"
#line 139 "/work/main/test/unit/test_recursive_dynamics.pf"
  call assertTrue(maxval(abs(kin%alpha0 - al0)) <= 1.0e-12_wp*maxval(abs(al0)), 'recursive alpha0', &
 & location=SourceLocation( &
 & 'test_recursive_dynamics.pf', &
 & 139) )
  if (anyExceptions()) return
#line 140 "/work/main/test/unit/test_recursive_dynamics.pf"
            call f_i(tree, kin, loads, f18)
            call body_kinematics(tree, x, xd, kin)
            call f_recursive(tree, kin, loads, fr)
#line 143 "/work/main/test/unit/test_recursive_dynamics.pf"
  call assertTrue(maxval(abs(fr - f18)) <= 1.0e-12_wp*maxval(abs(f18)), 'recursive f_i = eq 18 to 1e-12', &
 & location=SourceLocation( &
 & 'test_recursive_dynamics.pf', &
 & 143) )
  if (anyExceptions()) return
#line 144 "/work/main/test/unit/test_recursive_dynamics.pf"
            deallocate (x, xd, f18, fr)
        end do
    end subroutine test_recursive_f_equals_eq18

    !@test
    subroutine test_inertia_times_equals_a_v()
        type(rng_t) :: rng
        type(body_tree_t) :: tree
        type(kinematics_t) :: kin
        real(wp), allocatable :: x(:), xd(:), a(:, :), v(:), a0v(:)
        call rng%seed(56)
        call random_tree(tree, 36, rng)
        allocate (x(tree%ndof), xd(tree%ndof), a(tree%ndof, tree%ndof), v(tree%ndof))
        call random_state(rng, tree%ndof, x, xd)
        call random_state(rng, tree%ndof, v, xd)
        call kinematics_allocate(tree, kin)
        call partial_velocities(tree, x, xd, kin)
        call a_ij(tree, kin, a)
        a0v = matmul(a, v)
#line 163 "/work/main/test/unit/test_recursive_dynamics.pf"
  call assertTrue(maxval(abs(inertia_times(tree, kin, v) - a0v)) <= 1.0e-12_wp*maxval(abs(a0v)), 'a v in O(n)', &
 & location=SourceLocation( &
 & 'test_recursive_dynamics.pf', &
 & 163) )
  if (anyExceptions()) return
#line 164 "/work/main/test/unit/test_recursive_dynamics.pf"
    end subroutine test_inertia_times_equals_a_v

    !> The three solver paths on one model with prescribed coordinates
    !! (harmonic motions) and gravity: xddot_F and the power of the
    !! prescribed motions agree with the Gauss path.
    !@test
    subroutine test_solver_paths_agree()
        type(rng_t) :: rng
        type(body_tree_t) :: tree
        type(model_t) :: model
        type(dyn_workspace_t) :: wg, wc, wa
        real(wp), allocatable :: x(:), xd(:), xg(:), xc(:), xa(:)
        real(wp) :: pscale
        integer :: k, j, sg, sc, sa
        character(len=msglen) :: mg, mc, ma
        call rng%seed(78)
        do k = 1, size(sizes)
            call random_tree(tree, sizes(k), rng)
            call model_init(model, tree)
            do j = 1, tree%ndof
                if (tree%dof_body(j) == 1 .or. rng%uniform(zero, one) < 0.05_wp) then
                    model%prescribed(j) = .true.
                    model%motion(j) = motion_harmonic(rng%uniform(-0.2_wp, 0.2_wp), 0.1_wp, 20.0_wp, 0.3_wp)
                end if
            end do
            call dynamics_setup(model, wg)
            call dynamics_setup(model, wc)
            call dynamics_setup(model, wa)
            allocate (x(wg%nfree), xd(wg%nfree), xg(wg%nfree), xc(wg%nfree), xa(wg%nfree))
            call random_state(rng, wg%nfree, x, xd)
            model%solver = solver_gauss
            call dynamics_evaluate(model, wg, 0.013_wp, x, xd, xg, sg, mg)
            model%solver = solver_cholesky
            call dynamics_evaluate(model, wc, 0.013_wp, x, xd, xc, sc, mc)
            model%solver = solver_articulated
            call dynamics_evaluate(model, wa, 0.013_wp, x, xd, xa, sa, ma)
#line 200 "/work/main/test/unit/test_recursive_dynamics.pf"
  call assertEqual(0, sg, trim(mg), &
 & location=SourceLocation( &
 & 'test_recursive_dynamics.pf', &
 & 200) )
  if (anyExceptions()) return
#line 201 "/work/main/test/unit/test_recursive_dynamics.pf"
#line 201 "/work/main/test/unit/test_recursive_dynamics.pf"
  call assertEqual(0, sc, trim(mc), &
 & location=SourceLocation( &
 & 'test_recursive_dynamics.pf', &
 & 201) )
  if (anyExceptions()) return
#line 202 "/work/main/test/unit/test_recursive_dynamics.pf"
#line 202 "/work/main/test/unit/test_recursive_dynamics.pf"
  call assertEqual(0, sa, trim(ma), &
 & location=SourceLocation( &
 & 'test_recursive_dynamics.pf', &
 & 202) )
  if (anyExceptions()) return
#line 203 "/work/main/test/unit/test_recursive_dynamics.pf"
#line 203 "/work/main/test/unit/test_recursive_dynamics.pf"
  call assertTrue(maxval(abs(xc - xg)) <= 1.0e-10_wp*maxval(abs(xg)), 'CHOLESKY = GAUSS to 1e-10', &
 & location=SourceLocation( &
 & 'test_recursive_dynamics.pf', &
 & 203) )
  if (anyExceptions()) return
#line 204 "/work/main/test/unit/test_recursive_dynamics.pf"
#line 204 "/work/main/test/unit/test_recursive_dynamics.pf"
  call assertTrue(maxval(abs(xa - xg)) <= 1.0e-10_wp*maxval(abs(xg)), 'ABA = GAUSS to 1e-10', &
 & location=SourceLocation( &
 & 'test_recursive_dynamics.pf', &
 & 204) )
  if (anyExceptions()) return
#line 205 "/work/main/test/unit/test_recursive_dynamics.pf"
            pscale = 1.0e-10_wp*max(abs(wg%p_prescribed), one)
#line 206 "/work/main/test/unit/test_recursive_dynamics.pf"
  call assertTrue(abs(wa%p_prescribed - wg%p_prescribed) <= pscale, 'ABA lambda_P . xdot_P', &
 & location=SourceLocation( &
 & 'test_recursive_dynamics.pf', &
 & 206) )
  if (anyExceptions()) return
#line 207 "/work/main/test/unit/test_recursive_dynamics.pf"
#line 207 "/work/main/test/unit/test_recursive_dynamics.pf"
  call assertTrue(abs(wc%p_prescribed - wg%p_prescribed) <= pscale, 'CHOLESKY lambda_P . xdot_P', &
 & location=SourceLocation( &
 & 'test_recursive_dynamics.pf', &
 & 207) )
  if (anyExceptions()) return
#line 208 "/work/main/test/unit/test_recursive_dynamics.pf"
            deallocate (x, xd, xg, xc, xa)
        end do
    end subroutine test_solver_paths_agree

end module test_recursive_dynamics

module Wraptest_recursive_dynamics
   use FUnit
   use test_recursive_dynamics
   implicit none
   private

contains


end module Wraptest_recursive_dynamics

function test_recursive_dynamics_suite() result(suite)
   use FUnit
   use test_recursive_dynamics
   use Wraptest_recursive_dynamics
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_recursive_dynamics_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_composite_rigid_body_equals_eq17', &
      test_composite_rigid_body_equals_eq17))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_recursive_f_equals_eq18', &
      test_recursive_f_equals_eq18))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_inertia_times_equals_a_v', &
      test_inertia_times_equals_a_v))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_solver_paths_agree', &
      test_solver_paths_agree))
   call suite%addTest(t)


end function test_recursive_dynamics_suite

