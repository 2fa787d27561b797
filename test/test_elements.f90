!> Element forces against hand-computed values and mechanical principles:
!! discs (eqs 1-9), ligaments (eq 10), muscles (eq 11), joint-limit
!! dampers (eqs 12-13).
program test_elements
    use hn_kinds, only: wp, zero, one, msglen, pi
    use hn_tree, only: body_tree_t, tree_allocate, tree_build
    use hn_kinematics, only: kinematics_t, kinematics_allocate, partial_velocities
    use hn_loads, only: body_loads_t, loads_allocate, loads_clear
    use hn_discs, only: disc_t, disc_stiffness, disc_set_reference, disc_deformation, disc_resultants, &
                        apply_disc
    use hn_line_elements, only: ligament_t, ligament_tension, ligament_energy, muscle_t, muscle_tension, &
                                line_geometry_t, line_geometry, apply_line_tension
    use hn_joint_limits, only: joint_limit_t, limit_force, limit_damping
    use hn_rotation, only: cross
    use hn_testing, only: test_suite_t
    use hn_test_models, only: rng_t
    implicit none

    type(test_suite_t) :: suite
    type(rng_t) :: rng
    type(body_tree_t) :: tree
    type(disc_t) :: disc

    call two_body_tree(tree)
    disc = sample_disc()
    call test_disc_axial_hand_value()
    call test_disc_torsion_hand_value()
    call test_disc_shear_hand_value()
    call test_disc_bending_hand_value()
    call test_disc_viscous_axial()
    call test_timoshenko_tends_to_euler_bernoulli()
    call test_disc_rates_match_finite_differences()
    call test_disc_loads_conjugate_to_deformation()
    call test_disc_no_work_in_rigid_motion()
    call test_disc_equal_and_opposite()
    call test_disc_energy_balance()
    call test_ligament_hand_value()
    call test_ligament_slack_zero()
    call test_ligament_energy_derivative()
    call test_muscle_hand_value()
    call test_muscle_never_pushes()
    call test_muscle_activation()
    call test_line_element_no_work_in_rigid_motion()
    call test_limit_acts_toward_limit_only()
    call test_limit_damping_continuous()
    call test_limit_ramp_hand_value()
    call suite%finish()

contains

    !> Lower body (1) fixed to R by all 6 coordinates, upper body (2) on a
    !! joint 20 mm above; all 12 coordinates active.
    subroutine two_body_tree(tr)
        type(body_tree_t), intent(out) :: tr
        integer :: stat
        character(len=msglen) :: msg
        call tree_allocate(tr, 2)
        tr%mass = [0.5_wp, 0.4_wp]
        tr%joint_parent(:, 2) = [zero, zero, 0.01_wp]
        tr%joint_child(:, 2) = [zero, zero, -0.01_wp]
        call tree_build(tr, stat, msg)
    end subroutine two_body_tree

    function sample_disc() result(d)
        type(disc_t) :: d
        type(kinematics_t) :: kin
        integer :: i
        d%body_a = 1; d%body_b = 2
        d%pa = [zero, zero, 0.0075_wp]
        d%pb = [zero, zero, -0.0075_wp]
        d%area = 3.0e-4_wp; d%h = 4.5e-3_wp
        d%d1 = 1.0e7_wp; d%d2 = 2.0e4_wp; d%g = 2.0e6_wp
        d%ix = 1.1e-8_wp; d%iy = 1.3e-8_wp; d%j = 3.0e-8_wp; d%kshear = 1.2_wp
        call kin_at([(zero, i=1, 12)], [(zero, i=1, 12)], kin)
        call disc_set_reference(d, kin)
    end function sample_disc

    subroutine kin_at(x, xd, kin)
        real(wp), intent(in) :: x(:), xd(:)
        type(kinematics_t), intent(out) :: kin
        call kinematics_allocate(tree, kin)
        call partial_velocities(tree, x, xd, kin)
    end subroutine kin_at

    !> Resultants of the disc with body 2's own coordinates at q2 (rates qd2).
    function resultants_at(q2, qd2) result(s)
        real(wp), intent(in) :: q2(6), qd2(6)
        real(wp) :: s(6), q(6), qd(6), l(3, 3), p(3)
        type(kinematics_t) :: kin
        call kin_at([zero, zero, zero, zero, zero, zero, q2], [zero, zero, zero, zero, zero, zero, qd2], kin)
        call disc_deformation(disc, kin, q, qd, l, p)
        s = disc_resultants(disc, q, qd)
    end function resultants_at

    subroutine test_disc_axial_hand_value()
        real(wp) :: s(6)
        integer :: i
        s = resultants_at([zero, zero, 1.0e-4_wp, zero, zero, zero], [(zero, i=1, 6)])
        ! P = (A/h) d1 delta = 3e-4/4.5e-3 * 1e7 * 1e-4 = 66.667 N
        call suite%near(s(3), 66.6666666666667_wp, 1.0e-9_wp, 'disc axial force P = (A/h) d1 delta (eq 1)')
    end subroutine test_disc_axial_hand_value

    subroutine test_disc_torsion_hand_value()
        real(wp) :: s(6)
        integer :: i
        s = resultants_at([zero, zero, zero, zero, zero, 0.01_wp], [(zero, i=1, 6)])
        ! T = G J theta / h = 2e6 * 3e-8 * 0.01 / 4.5e-3 = 0.13333 N m
        call suite%near(s(6), 0.133333333333333_wp, 1.0e-12_wp, 'disc torque T = G J theta / h (eq 7)')
    end subroutine test_disc_torsion_hand_value

    subroutine test_disc_shear_hand_value()
        real(wp) :: s(6), phi, kb
        integer :: i
        s = resultants_at([1.0e-4_wp, zero, zero, zero, zero, zero], [(zero, i=1, 6)])
        ! x-z plane: Phi = 12 E Iy k/(G A h^2), V = 12 E Iy/(h^3 (1+Phi)) u, M = -6h E Iy/(h^3(1+Phi)) u
        phi = 12*1.0e7_wp*1.3e-8_wp*1.2_wp/(2.0e6_wp*3.0e-4_wp*4.5e-3_wp**2)
        kb = 1.0e7_wp*1.3e-8_wp/(4.5e-3_wp**3*(one + phi))
        call suite%check(abs(s(1) - 12*kb*1.0e-4_wp) < 1.0e-9_wp*abs(s(1)) .and. &
                         abs(s(5) + 6*4.5e-3_wp*kb*1.0e-4_wp) < 1.0e-9_wp*abs(s(5)), &
                         'disc shear: V and coupled moment of the Timoshenko beam (eqs 2-6, 8-9)')
    end subroutine test_disc_shear_hand_value

    subroutine test_disc_bending_hand_value()
        real(wp) :: k(6, 6), cond
        ! static condensation of shear at zero shear force: M/theta = E I / h
        k = disc_stiffness(disc)
        cond = k(5, 5) - k(1, 5)**2/k(1, 1)
        call suite%near(cond, disc%d1*disc%iy/disc%h, 1.0e-9_wp*cond, &
                        'disc bending with free shear: M/theta = E I / h')
    end subroutine test_disc_bending_hand_value

    subroutine test_disc_viscous_axial()
        real(wp) :: s(6)
        integer :: i
        s = resultants_at([(zero, i=1, 6)], [zero, zero, 0.1_wp, zero, zero, zero])
        ! P = (A/h) d2 delta' = 3e-4/4.5e-3 * 2e4 * 0.1 = 133.333 N
        call suite%near(s(3), 133.333333333333_wp, 1.0e-8_wp, "disc viscous axial force (A/h) d2 delta' (eq 1)")
    end subroutine test_disc_viscous_axial

    subroutine test_timoshenko_tends_to_euler_bernoulli()
        type(disc_t) :: d
        real(wp) :: k(6, 6), eb(4), ei, h, err
        d = disc
        d%g = 1.0e30_wp
        k = disc_stiffness(d)
        ei = d%d1*d%iy; h = d%h
        eb = [12*ei/h**3, -6*ei/h**2, 4*ei/h, zero]
        err = max(abs(k(1, 1) - eb(1))/eb(1), abs(k(1, 5) - eb(2))/abs(eb(2)), abs(k(5, 5) - eb(3))/eb(3))
        call suite%near(err, zero, 1.0e-12_wp, 'Timoshenko stiffness tends to Euler-Bernoulli as G -> infinity')
    end subroutine test_timoshenko_tends_to_euler_bernoulli

    subroutine random_state(x, xd)
        real(wp), intent(out) :: x(12), xd(12)
        integer :: i
        do i = 1, 12
            x(i) = rng%uniform(-0.4_wp, 0.4_wp)
            xd(i) = rng%uniform(-3.0_wp, 3.0_wp)
        end do
        x([1, 2, 3, 7, 8, 9]) = 0.005_wp*x([1, 2, 3, 7, 8, 9])
    end subroutine random_state

    subroutine test_disc_rates_match_finite_differences()
        real(wp) :: x(12), xd(12), q(6), qd(6), qp(6), qm(6), l(3, 3), p(3), dum(6), h
        type(kinematics_t) :: kin
        h = 1.0e-6_wp
        call random_state(x, xd)
        call kin_at(x, xd, kin); call disc_deformation(disc, kin, q, qd, l, p)
        call kin_at(x + h*xd, xd, kin); call disc_deformation(disc, kin, qp, dum, l, p)
        call kin_at(x - h*xd, xd, kin); call disc_deformation(disc, kin, qm, dum, l, p)
        call suite%near(maxval(abs((qp - qm)/(2*h) - qd))/maxval(abs(qd)), zero, 1.0e-7_wp, &
                        'disc deformation rates = finite differences of the deformations')
    end subroutine test_disc_rates_match_finite_differences

    !> Power of the disc loads on the two bodies = -s . qdot (so U = q^T K q/2 is exact).
    subroutine test_disc_loads_conjugate_to_deformation()
        real(wp) :: x(12), xd(12), q(6), qd(6), l(3, 3), p(3), s(6), power, u, pd
        type(kinematics_t) :: kin
        type(body_loads_t) :: loads
        integer :: k
        call random_state(x, xd)
        call kin_at(x, xd, kin)
        call loads_allocate(loads, 2, 12)
        call apply_disc(disc, kin, loads, s, u, pd)
        call disc_deformation(disc, kin, q, qd, l, p)
        power = zero
        do k = 1, 2
            power = power + dot_product(loads%force(:, k), kin%v(:, k)) + dot_product(loads%moment(:, k), kin%omega(:, k))
        end do
        call suite%near(power, -dot_product(s, qd), 1.0e-9_wp*abs(dot_product(s, qd)), &
                        'disc load power = -s . qdot (work-conjugate loads)')
    end subroutine test_disc_loads_conjugate_to_deformation

    !> Both bodies moving as one rigid body: the deformed disc does no work.
    subroutine test_disc_no_work_in_rigid_motion()
        real(wp) :: x(12), xd(12), s(6), power, scale, u, pd
        type(kinematics_t) :: kin
        type(body_loads_t) :: loads
        integer :: k
        call random_state(x, xd)
        xd(7:12) = zero          ! no relative motion of body 2
        call kin_at(x, xd, kin)
        call loads_allocate(loads, 2, 12)
        call apply_disc(disc, kin, loads, s, u, pd)
        power = zero; scale = zero
        do k = 1, 2
            power = power + dot_product(loads%force(:, k), kin%v(:, k)) + dot_product(loads%moment(:, k), kin%omega(:, k))
            scale = scale + abs(dot_product(loads%force(:, k), kin%v(:, k)))
        end do
        call suite%near(power/scale, zero, 1.0e-12_wp, 'disc does no net work in a rigid-body motion of the pair')
    end subroutine test_disc_no_work_in_rigid_motion

    subroutine test_disc_equal_and_opposite()
        real(wp) :: x(12), xd(12), s(6), ftot(3), mtot(3), u, pd
        type(kinematics_t) :: kin
        type(body_loads_t) :: loads
        integer :: k
        call random_state(x, xd)
        call kin_at(x, xd, kin)
        call loads_allocate(loads, 2, 12)
        call apply_disc(disc, kin, loads, s, u, pd)
        ftot = loads%force(:, 1) + loads%force(:, 2)
        mtot = zero
        do k = 1, 2
            mtot = mtot + loads%moment(:, k) + cross(kin%r(:, k), loads%force(:, k))
        end do
        call suite%check(maxval(abs(ftot)) < 1.0e-10_wp*maxval(abs(loads%force)) .and. &
                         maxval(abs(mtot)) < 1.0e-10_wp*maxval(abs(loads%moment)), &
                         'disc loads on the two bodies are equal and opposite (force and moment about R)')
    end subroutine test_disc_equal_and_opposite

    !> Power of the disc loads = -(dU/dt + dissipation), dU/dt by central
    !! differences of the stored energy along the motion.
    subroutine test_disc_energy_balance()
        real(wp) :: x(12), xd(12), s(6), u, pd, up, um, power, h
        type(kinematics_t) :: kin
        type(body_loads_t) :: loads
        integer :: k
        h = 1.0e-6_wp
        call random_state(x, xd)
        call loads_allocate(loads, 2, 12)
        call kin_at(x + h*xd, xd, kin); call apply_disc(disc, kin, loads, s, up, pd)
        call kin_at(x - h*xd, xd, kin); call apply_disc(disc, kin, loads, s, um, pd)
        call loads_clear(loads)
        call kin_at(x, xd, kin); call apply_disc(disc, kin, loads, s, u, pd)
        power = zero
        do k = 1, 2
            power = power + dot_product(loads%force(:, k), kin%v(:, k)) + dot_product(loads%moment(:, k), kin%omega(:, k))
        end do
        call suite%near(power, -((up - um)/(2*h) + pd), 1.0e-6_wp*abs(power), &
                        'disc: load power = -(dU/dt + dissipated power), U = q^T K q / 2')
    end subroutine test_disc_energy_balance

    function sample_ligament() result(g)
        type(ligament_t) :: g
        g%l1 = 2.0e4_wp; g%l2 = 3.0e7_wp; g%n = 2.2_wp; g%length0 = 0.02_wp
    end function sample_ligament

    subroutine test_ligament_hand_value()
        ! F = 2e4 * 1e-3 + 3e7 * (1e-3)^2.2 = 20 + 3e7 * 2.5119e-7 = 27.5357 N
        call suite%near(ligament_tension(sample_ligament(), 0.021_wp), 20.0_wp + 3.0e7_wp*(1.0e-3_wp)**2.2_wp, &
                        1.0e-10_wp, 'ligament tension F = l1 d + l2 d^n (eq 10)')
    end subroutine test_ligament_hand_value

    subroutine test_ligament_slack_zero()
        call suite%check(ligament_tension(sample_ligament(), 0.019_wp) == zero .and. &
                         ligament_tension(sample_ligament(), 0.02_wp) == zero, &
                         'ligament is slack (zero force) at or below its slack length')
    end subroutine test_ligament_slack_zero

    subroutine test_ligament_energy_derivative()
        real(wp) :: h, du
        h = 1.0e-8_wp
        du = (ligament_energy(sample_ligament(), 0.0215_wp + h) - ligament_energy(sample_ligament(), 0.0215_wp - h))/(2*h)
        call suite%near(du, ligament_tension(sample_ligament(), 0.0215_wp), 1.0e-6_wp, &
                        'ligament energy derivative = tension')
    end subroutine test_ligament_energy_derivative

    subroutine test_muscle_hand_value()
        type(muscle_t) :: m
        m%m1 = 800.0_wp; m%m2 = 60.0_wp; m%length0 = 0.1_wp
        ! 800 * 0.005 + 60 * 0.2 = 16 N
        call suite%near(muscle_tension(m, 0.105_wp, 0.2_wp, zero), 16.0_wp, 1.0e-12_wp, &
                        "muscle tension F = m1 d + m2 d' (eq 11)")
    end subroutine test_muscle_hand_value

    subroutine test_muscle_never_pushes()
        type(muscle_t) :: m
        m%m1 = 800.0_wp; m%m2 = 60.0_wp; m%length0 = 0.1_wp
        call suite%check(muscle_tension(m, 0.095_wp, zero, zero) == zero .and. &
                         muscle_tension(m, 0.105_wp, -0.5_wp, zero) == zero .and. &
                         muscle_tension(m, 0.095_wp, -1.0_wp, zero) == zero, &
                         'muscle never pushes: zero when m1 d + m2 d'' < 0')
    end subroutine test_muscle_never_pushes

    subroutine test_muscle_activation()
        type(muscle_t) :: m
        m%m1 = 800.0_wp; m%m2 = 60.0_wp; m%length0 = 0.1_wp; m%fmax = 300.0_wp
        ! slack and shortening, yet half activation pulls: 800 (-0.01) + 60 (-0.5) + 0.5 * 300 = 112 N
        call suite%near(muscle_tension(m, 0.09_wp, -0.5_wp, 0.5_wp), 112.0_wp, 1.0e-12_wp, &
                        'muscle activation adds a(t) Fmax to the passive law')
    end subroutine test_muscle_activation

    subroutine test_line_element_no_work_in_rigid_motion()
        real(wp) :: x(12), xd(12), power
        type(kinematics_t) :: kin
        type(body_loads_t) :: loads
        type(line_geometry_t) :: g
        integer :: k
        call random_state(x, xd)
        xd(7:12) = zero
        call kin_at(x, xd, kin)
        call loads_allocate(loads, 2, 12)
        call line_geometry(kin, 1, [0.01_wp, 0.02_wp, 0.005_wp], 2, [-0.02_wp, 0.01_wp, -0.004_wp], g)
        call apply_line_tension(loads, kin, 1, 2, g, 150.0_wp)
        power = zero
        do k = 1, 2
            power = power + dot_product(loads%force(:, k), kin%v(:, k)) + dot_product(loads%moment(:, k), kin%omega(:, k))
        end do
        call suite%check(abs(g%rate) < 1.0e-13_wp .and. abs(power) < 1.0e-11_wp .and. &
                         maxval(abs(loads%force(:, 1) + loads%force(:, 2))) < 1.0e-12_wp, &
                         'line element: equal and opposite, no work and no length change in rigid motion')
    end subroutine test_line_element_no_work_in_rigid_motion

    function sample_limit() result(lim)
        type(joint_limit_t) :: lim
        lim%xmin = -0.2_wp; lim%xmax = 0.3_wp; lim%xneutral = zero
        lim%c0 = 0.05_wp; lim%c1 = 4.0_wp
    end function sample_limit

    subroutine test_limit_acts_toward_limit_only()
        type(joint_limit_t) :: lim
        lim = sample_limit()
        call suite%check(limit_force(lim, 0.35_wp, 1.0_wp) < zero .and. limit_force(lim, 0.35_wp, -1.0_wp) == zero &
                         .and. limit_force(lim, -0.25_wp, -1.0_wp) > zero .and. limit_force(lim, -0.25_wp, 1.0_wp) == zero &
                         .and. limit_force(lim, 0.1_wp, 1.0_wp) < zero .and. limit_force(lim, 0.1_wp, -1.0_wp) == zero, &
                         'one-way damper acts only while moving towards a limit (eq 12)')
    end subroutine test_limit_acts_toward_limit_only

    subroutine test_limit_damping_continuous()
        type(joint_limit_t) :: lim
        real(wp) :: e
        lim = sample_limit()
        e = 1.0e-12_wp
        call suite%check(abs(limit_damping(lim, lim%xmax + e) - limit_damping(lim, lim%xmax - e)) < 1.0e-10_wp .and. &
                         abs(limit_damping(lim, lim%xmin + e) - limit_damping(lim, lim%xmin - e)) < 1.0e-10_wp, &
                         'damping coefficient is continuous at both limits (eq 13)')
    end subroutine test_limit_damping_continuous

    subroutine test_limit_ramp_hand_value()
        ! C = 0.05 + 4 * (0.4 - 0.3) = 0.45; Q = -0.45 * 2 = -0.9
        call suite%near(limit_force(sample_limit(), 0.4_wp, 2.0_wp), -0.9_wp, 1.0e-14_wp, &
                        'damping C0 + C1 |X - Xmax| beyond the limit (eq 13)')
    end subroutine test_limit_ramp_hand_value

end program test_elements
