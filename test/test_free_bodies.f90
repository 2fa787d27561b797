!> Conservation laws of free systems: a torque-free asymmetric rigid body
!! (energy and angular momentum; stability of rotation about the principal
!! axes) and a free-floating tree with internal springs (momentum).
program test_free_bodies
    use hn_kinds, only: wp, zero, one, msglen
    use hn_tree, only: body_tree_t, tree_allocate, tree_build
    use hn_model, only: model_t, model_init
    use hn_dynamics, only: model_ode_t, model_ode_init
    use hn_kinematics, only: partial_velocities, kinetic_energy, linear_momentum, angular_momentum
    use hn_integrators, only: dopri5_t
    use hn_rotation, only: norm3
    use hn_testing, only: test_suite_t
    use hn_test_models, only: rng_t, random_tree
    implicit none

    real(wp), parameter :: spin = 2.0_wp, eps = 1.0e-4_wp, t_end = 10.0_wp
    type(test_suite_t) :: suite

    call test_spin_about_largest_axis()
    call test_spin_about_smallest_axis()
    call test_spin_about_intermediate_axis()
    call test_free_floating_tree_momentum()
    call suite%finish()

contains

    !> One free body with principal inertia diag(ip) in its frame, spinning
    !! about body z at rate `spin` with a perturbation eps*spin about x and y.
    !! Returns the worst relative drift of energy and of angular momentum,
    !! and the largest tilt of body z from its initial direction [rad]
    !! (the run stops early once the tilt passes 0.5 rad).
    subroutine spin_run(ip, drift_t, drift_h, tilt)
        real(wp), intent(in) :: ip(3)
        real(wp), intent(out) :: drift_t, drift_h, tilt
        type(body_tree_t) :: tree
        type(model_t) :: model
        type(model_ode_t) :: sys
        type(dopri5_t) :: integ
        real(wp) :: y(16), t, t0e, h0(3), zax(3)
        integer :: stat, i
        character(len=msglen) :: msg
        call tree_allocate(tree, 1)
        tree%inertia(:, :, 1) = zero
        do i = 1, 3
            tree%inertia(i, i, 1) = ip(i)
        end do
        tree%mass(1) = 3.0_wp
        call tree_build(tree, stat, msg)
        call model_init(model, tree)
        model%gravity = zero
        call model_ode_init(sys, model)
        y = zero
        y(7:9) = [0.1_wp, -0.2_wp, 0.05_wp]          ! drifting mass centre
        y(10:12) = [eps*spin, eps*spin, spin]        ! Bryant rates = body rates at zero angles
        call integ%set_tolerances(1.0e-12_wp, 1.0e-14_wp); call integ%set_step(1.0e-3_wp)
        t = zero
        call body_invariants(sys, y, t0e, h0, zax)
        call integ%init(sys, t, y, stat, msg)
        drift_t = zero; drift_h = zero; tilt = zero
        do while (t < t_end - 1.0e-9_wp)
            t = t + 0.01_wp
            call integ%advance(sys, t, y, huge(one), stat, msg)
            if (stat /= 0) error stop trim(msg)
            block
                real(wp) :: te, hh(3), z(3)
                call body_invariants(sys, y, te, hh, z)
                drift_t = max(drift_t, abs(te - t0e)/t0e)
                drift_h = max(drift_h, norm3(hh - h0)/norm3(h0))
                tilt = max(tilt, acos(max(-one, min(one, dot_product(z, zax)))))
            end block
            if (tilt > 0.5_wp) exit
        end do
    end subroutine spin_run

    !> Energy, angular momentum and body z axis of the one-body system.
    subroutine body_invariants(sys, yy, te, hh, z)
        type(model_ode_t), intent(inout) :: sys
        real(wp), intent(in) :: yy(:)
        real(wp), intent(out) :: te, hh(3), z(3)
        call partial_velocities(sys%model%tree, yy(1:6), yy(7:12), sys%ws%kin)
        te = kinetic_energy(sys%model%tree, sys%ws%kin)
        hh = angular_momentum(sys%model%tree, sys%ws%kin)
        z = sys%ws%kin%s(:, 3, 1)
    end subroutine body_invariants

    subroutine report(name, ok, dt, dh, tilt)
        character(len=*), intent(in) :: name
        logical, intent(in) :: ok
        real(wp), intent(in) :: dt, dh, tilt
        character(len=120) :: d
        write (d, '(a,es9.2,a,es9.2,a,es9.2,a)') 'energy drift ', dt, ', momentum drift ', dh, &
            ', max tilt ', tilt, ' rad'
        call suite%check(ok, name, d)
    end subroutine report

    subroutine test_spin_about_largest_axis()
        real(wp) :: dt, dh, tilt
        call spin_run([0.010_wp, 0.020_wp, 0.030_wp], dt, dh, tilt)
        call report('spin about the largest axis: stable, energy and momentum conserved to 1e-9 over 10 s', &
                    dt < 1.0e-9_wp .and. dh < 1.0e-9_wp .and. tilt < 20*eps, dt, dh, tilt)
    end subroutine test_spin_about_largest_axis

    subroutine test_spin_about_smallest_axis()
        real(wp) :: dt, dh, tilt
        call spin_run([0.020_wp, 0.030_wp, 0.010_wp], dt, dh, tilt)
        call report('spin about the smallest axis: stable, energy and momentum conserved to 1e-9 over 10 s', &
                    dt < 1.0e-9_wp .and. dh < 1.0e-9_wp .and. tilt < 20*eps, dt, dh, tilt)
    end subroutine test_spin_about_smallest_axis

    subroutine test_spin_about_intermediate_axis()
        real(wp) :: dt, dh, tilt
        call spin_run([0.010_wp, 0.030_wp, 0.020_wp], dt, dh, tilt)
        call report('spin about the intermediate axis: perturbation grows past 0.5 rad, invariants kept', &
                    tilt > 0.5_wp .and. dt < 1.0e-9_wp .and. dh < 1.0e-9_wp, dt, dh, tilt)
    end subroutine test_spin_about_intermediate_axis

    !> Five bodies, all 6 coordinates of each free, no gravity, joined by
    !! internal spring-dampers only: linear and angular momentum constant.
    subroutine test_free_floating_tree_momentum()
        type(body_tree_t) :: tree
        type(model_t) :: model
        type(model_ode_t) :: sys
        type(dopri5_t) :: integ
        type(rng_t) :: rng
        real(wp), allocatable :: y(:)
        real(wp) :: t, p0(3), h0(3), dp, dh, pscale, hscale
        integer :: stat, e, n
        character(len=msglen) :: msg
        character(len=120) :: d
        call random_tree(tree, 5, rng)
        call model_init(model, tree)
        model%gravity = zero
        deallocate (model%springs); allocate (model%springs(6))
        do e = 1, 6
            model%springs(e)%body_a = 1 + mod(e - 1, 5)
            model%springs(e)%body_b = 1 + mod(e + 1, 5)
            model%springs(e)%point_a = [rng%uniform(-0.05_wp, 0.05_wp), rng%uniform(-0.05_wp, 0.05_wp), 0.03_wp]
            model%springs(e)%point_b = [rng%uniform(-0.05_wp, 0.05_wp), rng%uniform(-0.05_wp, 0.05_wp), -0.03_wp]
            model%springs(e)%length0 = 0.04_wp
            model%springs(e)%stiffness = 500.0_wp
            model%springs(e)%damping = 0.5_wp
        end do
        call model_ode_init(sys, model)
        n = tree%ndof
        allocate (y(2*n + 4))
        y = zero
        do e = 1, 2*n
            y(e) = merge(rng%uniform(-0.3_wp, 0.3_wp), rng%uniform(-1.0_wp, 1.0_wp), e <= n)
        end do
        call partial_velocities(sys%model%tree, y(1:n), y(n + 1:2*n), sys%ws%kin)
        p0 = linear_momentum(sys%model%tree, sys%ws%kin)
        h0 = angular_momentum(sys%model%tree, sys%ws%kin)
        pscale = sum(tree%mass)*maxval(abs(y(n + 1:2*n)))
        hscale = norm3(h0) + 0.1_wp*pscale
        call integ%set_tolerances(1.0e-12_wp, 1.0e-14_wp); call integ%set_step(1.0e-4_wp)
        t = zero; dp = zero; dh = zero
        call integ%init(sys, t, y, stat, msg)
        do while (t < 2.0_wp - 1.0e-9_wp)
            t = t + 0.05_wp
            call integ%advance(sys, t, y, huge(one), stat, msg)
            if (stat /= 0) error stop trim(msg)
            call partial_velocities(sys%model%tree, y(1:n), y(n + 1:2*n), sys%ws%kin)
            dp = max(dp, norm3(linear_momentum(sys%model%tree, sys%ws%kin) - p0)/pscale)
            dh = max(dh, norm3(angular_momentum(sys%model%tree, sys%ws%kin) - h0)/hscale)
        end do
        write (d, '(a,es9.2,a,es9.2,a,i0,a)') 'linear ', dp, ', angular ', dh, ' (', sys%nevals, ' evaluations)'
        call suite%check(dp < 1.0e-9_wp .and. dh < 1.0e-9_wp, &
                         'free-floating tree with internal springs: momentum constant over 2 s', d)
    end subroutine test_free_floating_tree_momentum

end program test_free_bodies
