!> Random 9-body 54-DOF tree at random states: the recursive partial
!! velocities, a_ij and f_i against finite differences of positions and
!! orientations and against Lagrange's equations.
program test_kane_tree
    use hn_kinds, only: wp, zero, one, msglen
    use hn_tree, only: body_tree_t
    use hn_kinematics, only: kinematics_t, kinematics_allocate, partial_velocities, kinetic_energy
    use hn_loads, only: body_loads_t, loads_allocate
    use hn_kane, only: a_ij, f_i, generalized_active_forces
    use hn_model, only: model_t, model_init
    use hn_forces, only: compute_loads, element_output_t, element_output_allocate
    use hn_line_elements, only: spring_t
    use hn_linsolve, only: spd_rcond
    use hn_testing, only: test_suite_t
    use hn_test_models, only: rng_t, random_tree
    implicit none

    integer, parameter :: nb = 9, nstates = 3
    real(wp), parameter :: h = 1.0e-4_wp   ! central-difference step in x
    real(wp), parameter :: ht = 2.0e-6_wp  ! step along xd for body velocities (|xd| <= 3)
    type(test_suite_t) :: suite
    type(rng_t) :: rng
    type(model_t) :: model
    type(body_tree_t) :: tree
    real(wp), allocatable :: x(:), xd(:)
    integer :: istate, n, j
    character(len=32) :: tag

    call random_tree(tree, nb, rng)
    call model_init(model, tree)
    call add_random_springs(model, rng)
    n = tree%ndof
    call suite%check(n == 54, 'random tree has 54 active coordinates')
    allocate (x(n), xd(n))
    do istate = 1, nstates
        do j = 1, n
            if (tree%dof_local(j) <= 3) then
                x(j) = rng%uniform(-0.02_wp, 0.02_wp)
                xd(j) = rng%uniform(-0.5_wp, 0.5_wp)
            else
                x(j) = rng%uniform(-1.2_wp, 1.2_wp)
                xd(j) = rng%uniform(-3.0_wp, 3.0_wp)
            end if
        end do
        write (tag, '(a,i0)') ' (state ', istate
        tag = trim(tag)//')'
        call test_a_ij_positive_definite(trim(tag))
        call test_partial_velocities_fd(trim(tag))
        call test_partial_derivatives_fd(trim(tag))
        call test_kinetic_energy_direct(trim(tag))
        call test_a_ij_polarization(trim(tag))
        call test_gravity_generalized_force(trim(tag))
        call test_f_i_lagrange(trim(tag))
    end do
    call suite%finish()

contains

    subroutine add_random_springs(model, rng)
        type(model_t), intent(inout) :: model
        type(rng_t), intent(inout) :: rng
        integer :: e
        deallocate (model%springs)
        allocate (model%springs(4))
        do e = 1, 4
            model%springs(e)%body_a = e - 1
            model%springs(e)%body_b = e + 3
            model%springs(e)%point_a = [rng%uniform(-0.05_wp, 0.05_wp), rng%uniform(-0.05_wp, 0.05_wp), 0.02_wp]
            model%springs(e)%point_b = [rng%uniform(-0.05_wp, 0.05_wp), rng%uniform(-0.05_wp, 0.05_wp), 0.02_wp]
            model%springs(e)%length0 = 0.05_wp
            model%springs(e)%stiffness = 2000.0_wp
            model%springs(e)%damping = 3.0_wp
        end do
    end subroutine add_random_springs

    !> Kinematics at (x, xd).
    subroutine kin_at(xx, xxd, kin)
        real(wp), intent(in) :: xx(:), xxd(:)
        type(kinematics_t), intent(out) :: kin
        call kinematics_allocate(tree, kin)
        call partial_velocities(tree, xx, xxd, kin)
    end subroutine kin_at

    !> Kinetic energy at (x, xd) from finite differences of positions and
    !! orientations along xd: independent of the partial velocities.
    real(wp) function t_direct(xx, xxd) result(t)
        real(wp), intent(in) :: xx(:), xxd(:)
        type(kinematics_t) :: kp, km, k0
        real(wp) :: v(3), sd(3, 3), w(3, 3), om(3)
        integer :: k
        call kin_at(xx + ht*xxd, xxd, kp)
        call kin_at(xx - ht*xxd, xxd, km)
        call kin_at(xx, xxd, k0)
        t = zero
        do k = 1, nb
            v = (kp%r(:, k) - km%r(:, k))/(2*ht)
            sd = (kp%s(:, :, k) - km%s(:, :, k))/(2*ht)
            w = matmul(sd, transpose(k0%s(:, :, k)))      ! skew(omega)
            om = [w(3, 2) - w(2, 3), w(1, 3) - w(3, 1), w(2, 1) - w(1, 2)]*0.5_wp
            t = t + 0.5_wp*tree%mass(k)*dot_product(v, v) &
                + 0.5_wp*dot_product(om, matmul(k0%inertia_r(:, :, k), om))
        end do
    end function t_direct

    real(wp) function quad_form(a, v) result(s)
        real(wp), intent(in) :: a(:, :), v(:)
        s = dot_product(v, matmul(a, v))
    end function quad_form

    subroutine test_a_ij_positive_definite(tag)
        character(len=*), intent(in) :: tag
        type(kinematics_t) :: kin
        real(wp) :: a(n, n), rcond
        character(len=64) :: d
        call kin_at(x, xd, kin)
        call a_ij(tree, kin, a)
        call spd_rcond(a, rcond)
        write (d, '(a,es10.3)') 'rcond ', rcond
        call suite%check(rcond > 1.0e-12_wp, 'a_ij is symmetric positive definite'//tag, d)
    end subroutine test_a_ij_positive_definite

    !> v_pj = dr_p/dx_j and skew(omega_pj) = (dS_p/dx_j) S_p^T by central differences.
    subroutine test_partial_velocities_fd(tag)
        character(len=*), intent(in) :: tag
        type(kinematics_t) :: k0, kp, km
        real(wp) :: e(n), err, ref, dv(3), sd(3, 3), w(3, 3), om(3)
        integer :: j, p
        call kin_at(x, xd, k0)
        err = zero; ref = zero
        do j = 1, n
            e = zero; e(j) = h
            call kin_at(x + e, xd, kp)
            call kin_at(x - e, xd, km)
            do p = 1, nb
                dv = (kp%r(:, p) - km%r(:, p))/(2*h)
                sd = (kp%s(:, :, p) - km%s(:, :, p))/(2*h)
                w = matmul(sd, transpose(k0%s(:, :, p)))
                om = 0.5_wp*[w(3, 2) - w(2, 3), w(1, 3) - w(3, 1), w(2, 1) - w(1, 2)]
                err = max(err, maxval(abs(dv - k0%vp(:, j, p))), maxval(abs(om - k0%w(:, j, p))))
                ref = max(ref, maxval(abs(k0%vp(:, j, p))), maxval(abs(k0%w(:, j, p))))
            end do
        end do
        call suite%near(err/ref, zero, 1.0e-6_wp, 'partial velocities v_pjk, omega_pjk = finite differences'//tag)
    end subroutine test_partial_velocities_fd

    !> d/dt v_pj and d/dt omega_pj = (partials at x + h xd - at x - h xd) / 2h.
    subroutine test_partial_derivatives_fd(tag)
        character(len=*), intent(in) :: tag
        type(kinematics_t) :: k0, kp, km
        real(wp) :: err, ref
        call kin_at(x, xd, k0)
        call kin_at(x + h*xd, xd, kp)
        call kin_at(x - h*xd, xd, km)
        err = max(maxval(abs((kp%vp - km%vp)/(2*h) - k0%vd)), maxval(abs((kp%w - km%w)/(2*h) - k0%wd)))
        ref = max(maxval(abs(k0%vd)), maxval(abs(k0%wd)))
        call suite%near(err/ref, zero, 1.0e-6_wp, 'time derivatives of the partials = finite differences'//tag)
    end subroutine test_partial_derivatives_fd

    subroutine test_kinetic_energy_direct(tag)
        character(len=*), intent(in) :: tag
        type(kinematics_t) :: kin
        real(wp) :: a(n, n), t1, t2
        call kin_at(x, xd, kin)
        call a_ij(tree, kin, a)
        t1 = 0.5_wp*quad_form(a, xd)
        t2 = t_direct(x, xd)
        call suite%near(t1/t2, one, 1.0e-9_wp, '1/2 xd^T a xd = sum of body kinetic energies'//tag)
    end subroutine test_kinetic_energy_direct

    !> Every entry: a_ij = T(e_i + e_j) - T(e_i) - T(e_j) with T computed directly.
    subroutine test_a_ij_polarization(tag)
        character(len=*), intent(in) :: tag
        type(kinematics_t) :: kin
        real(wp) :: a(n, n), ti(n), ei(n), ej(n), err, aij
        integer :: i, j
        call kin_at(x, xd, kin)
        call a_ij(tree, kin, a)
        do i = 1, n
            ei = zero; ei(i) = one
            ti(i) = t_direct(x, ei)
        end do
        err = zero
        do i = 1, n, 5
            do j = 1, n, 3
                ei = zero; ei(i) = one
                ej = zero; ej(j) = one
                if (i == j) then
                    aij = 2*ti(i)
                else
                    aij = t_direct(x, ei + ej) - ti(i) - ti(j)
                end if
                err = max(err, abs(aij - a(i, j)))
            end do
        end do
        call suite%near(err/maxval(abs(a)), zero, 1.0e-9_wp, &
                        'a_ij entries from the kinetic energy by polarization'//tag)
    end subroutine test_a_ij_polarization

    !> Gravity: F_i = -dV/dx_i with V = -sum m_p g.r_p, by central differences.
    subroutine test_gravity_generalized_force(tag)
        character(len=*), intent(in) :: tag
        type(model_t) :: gm
        type(kinematics_t) :: kin, kp, km
        type(body_loads_t) :: loads
        type(element_output_t) :: eo
        real(wp) :: fa(n), e(n), dv, err
        integer :: j
        gm = model
        deallocate (gm%springs); allocate (gm%springs(0))
        call kin_at(x, xd, kin)
        call loads_allocate(loads, nb, n)
        call element_output_allocate(gm, eo)
        call compute_loads(gm, zero, kin, x, xd, loads, eo)
        call generalized_active_forces(tree, kin, loads, fa)
        err = zero
        do j = 1, n
            e = zero; e(j) = h
            call kin_at(x + e, xd, kp)
            call kin_at(x - e, xd, km)
            dv = (potential(kp) - potential(km))/(2*h)
            err = max(err, abs(fa(j) + dv))
        end do
        call suite%near(err/maxval(abs(fa)), zero, 1.0e-7_wp, 'gravity F_i = -dV/dx_i'//tag)
    end subroutine test_gravity_generalized_force

    real(wp) function potential(kin) result(v)
        type(kinematics_t), intent(in) :: kin
        integer :: k
        v = zero
        do k = 1, nb
            v = v - tree%mass(k)*dot_product(model%gravity, kin%r(:, k))
        end do
    end function potential

    !> f_i = F_i - adot_ij xd_j + dT/dx_i (Lagrange), adot along xd and
    !! dT/dx by central differences; F_i from gravity and springs.
    subroutine test_f_i_lagrange(tag)
        character(len=*), intent(in) :: tag
        type(kinematics_t) :: kin, kp, km
        type(body_loads_t) :: loads
        type(element_output_t) :: eo
        real(wp) :: ap(n, n), am(n, n), f(n), fa(n), lag(n), e(n)
        integer :: j
        call kin_at(x, xd, kin)
        call loads_allocate(loads, nb, n)
        call element_output_allocate(model, eo)
        call compute_loads(model, zero, kin, x, xd, loads, eo)
        call generalized_active_forces(tree, kin, loads, fa)
        call f_i(tree, kin, loads, f)
        call kin_at(x + h*xd, xd, kp); call a_ij(tree, kp, ap)
        call kin_at(x - h*xd, xd, km); call a_ij(tree, km, am)
        lag = fa - matmul((ap - am)/(2*h), xd)
        do j = 1, n
            e = zero; e(j) = h
            call kin_at(x + e, xd, kp); call a_ij(tree, kp, ap)
            call kin_at(x - e, xd, km); call a_ij(tree, km, am)
            lag(j) = lag(j) + 0.5_wp*quad_form((ap - am)/(2*h), xd)
        end do
        call suite%near(maxval(abs(f - lag))/maxval(abs(f)), zero, 1.0e-6_wp, &
                        'f_i = F_i - adot_ij xd_j + dT/dx_i (Lagrange)'//tag)
    end subroutine test_f_i_lagrange

end program test_kane_tree
