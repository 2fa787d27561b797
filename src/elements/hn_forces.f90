!> Assembly of the applied loads of a model at one instant: gravity, the
!! element families (discs, ligaments, muscles, joint-limit dampers,
!! springs), posture-holding generalized forces and applied load tables,
!! as body loads and generalized forces; plus each element's output.
module hn_forces
    use hn_kinds, only: wp, zero
    use hn_model, only: model_t, fam_discs, fam_ligaments, fam_muscles, fam_limits, fam_springs
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t, loads_clear
    use hn_line_elements, only: line_geometry_t, line_geometries, apply_line_tensions, spring_tension, &
                                spring_energy, ligament_tension, muscle_tension, ligament_energy, &
                                muscle_law_value, muscle_hill, muscle_geometries, apply_muscle_tensions, max_via
    use hn_discs, only: apply_disc
    use hn_joint_limits, only: limit_force, range_moment, range_energy
    use hn_applied, only: apply_applied_load, applied_vector, applied_couple
    use hn_tables, only: table_value
    use hn_muscle, only: activation_value
    use hn_rotation, only: cross
    implicit none
    private

    public :: element_output_t, element_output_allocate, compute_loads, switch_count, switching_functions, &
              muscle_activation

    !> What each element does at the current instant.
    type :: element_output_t
        real(wp), allocatable :: disc(:, :)         !! (6, nd) resultants: shear x, y, axial, bending x, y, torque
        real(wp), allocatable :: ligament(:, :)     !! (2, nl) tension [N], length [m]
        real(wp), allocatable :: muscle(:, :)       !! (3, nm) tension [N], length [m], activation
        real(wp), allocatable :: limit(:)           !! (nlim) generalized force [N or N m]
        real(wp), allocatable :: spring(:)          !! (ns) tension [N]
        real(wp) :: u_elastic = zero                !! energy stored in discs, ligaments, springs [J]
        real(wp) :: p_diss = zero                   !! power dissipated by discs, springs, joint dampers [W]
        real(wp) :: p_muscle = zero                 !! power absorbed by the muscles [W]
        real(wp) :: p_applied = zero                !! power of the applied force and couple tables [W]
        type(line_geometry_t), allocatable :: gl(:)       !! (nl) geometry of the ligaments
        type(line_geometry_t), allocatable :: gm(:)       !! (nm) path geometry of the muscles
        type(line_geometry_t), allocatable :: gs(:)       !! (ns) geometry of the springs
        type(line_geometry_t), allocatable :: gseg(:, :)  !! (max_via + 1, nm) geometry of the muscles' segments
    end type element_output_t

contains

    !> Size the element outputs of a model.
    pure subroutine element_output_allocate(model, eo)
        type(model_t), intent(in) :: model       !! the model
        type(element_output_t), intent(out) :: eo !! outputs sized for its elements, zero
        allocate (eo%disc(6, size(model%discs)), eo%ligament(2, size(model%ligaments)))
        allocate (eo%muscle(3, size(model%muscles)), eo%limit(size(model%limits)))
        allocate (eo%spring(size(model%springs)))
        allocate (eo%gl(size(model%ligaments)), eo%gm(size(model%muscles)), eo%gs(size(model%springs)))
        allocate (eo%gseg(max_via + 1, size(model%muscles)))
        eo%disc = zero; eo%ligament = zero; eo%muscle = zero; eo%limit = zero; eo%spring = zero
    end subroutine element_output_allocate

    !> All applied loads at time t for the kinematic state kin (x, xd the
    !! active coordinates and rates the kinematics was computed from).
    pure subroutine compute_loads(model, t, kin, x, xd, loads, eo)
        type(model_t), intent(in) :: model       !! the model
        real(wp), intent(in) :: t                !! time [s]
        type(kinematics_t), intent(in) :: kin    !! kinematics at (x, xd)
        real(wp), intent(in) :: x(:)             !! active coordinates [m, rad]
        real(wp), intent(in) :: xd(:)            !! their rates [m/s, rad/s]
        type(body_loads_t), intent(inout) :: loads !! body loads, every element's and applied load's added
        type(element_output_t), intent(inout) :: eo !! element outputs, energies and powers
        integer :: k, e
        real(wp) :: u, pd, v(3), p(3), pv(3)

        call loads_clear(loads)
        eo%u_elastic = zero; eo%p_diss = zero; eo%p_muscle = zero; eo%p_applied = zero
        do k = 1, model%tree%nbody
            loads%force(:, k) = model%tree%mass(k)*model%gravity
        end do
        loads%q = model%q_hold

        if (model%family_on(fam_discs)) then
            do e = 1, size(model%discs)
                call apply_disc(model%discs(e), kin, loads, eo%disc(:, e), u, pd)
                eo%u_elastic = eo%u_elastic + u
                eo%p_diss = eo%p_diss + pd
            end do
        end if
        if (model%family_on(fam_ligaments)) then
            associate (gl => eo%gl)
                call line_geometries(kin, model%ligaments, gl)
                eo%ligament(1, :) = ligament_tension(model%ligaments, gl%length)
                eo%ligament(2, :) = gl%length
                call apply_line_tensions(loads, kin, model%ligaments, gl, eo%ligament(1, :))
                eo%u_elastic = eo%u_elastic + sum(ligament_energy(model%ligaments, gl%length))
            end associate
        end if
        if (model%family_on(fam_muscles)) then
            associate (gm => eo%gm)
                call muscle_geometries(kin, model%muscles, gm, eo%gseg)
                do e = 1, size(model%muscles)
                    eo%muscle(3, e) = muscle_activation(model, e, t)
                end do
                eo%muscle(1, :) = muscle_tension(model%muscles, gm%length, gm%rate, eo%muscle(3, :))
                eo%muscle(2, :) = gm%length
                call apply_muscle_tensions(loads, kin, model%muscles, eo%gseg, eo%muscle(1, :))
                eo%p_muscle = eo%p_muscle + sum(eo%muscle(1, :)*gm%rate)
            end associate
        end if
        if (model%family_on(fam_limits)) then
            do e = 1, size(model%limits)
                associate (lim => model%limits(e))
                    eo%limit(e) = limit_force(lim, x(lim%dof), xd(lim%dof))
                    loads%q(lim%dof) = loads%q(lim%dof) + eo%limit(e)
                    eo%p_diss = eo%p_diss - eo%limit(e)*xd(lim%dof)
                end associate
            end do
            do e = 1, size(model%ranges)
                associate (r => model%ranges(e))
                    loads%q(r%dof) = loads%q(r%dof) + range_moment(r, x(r%dof))
                    eo%u_elastic = eo%u_elastic + range_energy(r, x(r%dof))
                end associate
            end do
        end if
        if (model%family_on(fam_springs)) then
            associate (gs => eo%gs)
                call line_geometries(kin, model%springs, gs)
                eo%spring = spring_tension(model%springs, gs%length, gs%rate)
                call apply_line_tensions(loads, kin, model%springs, gs, eo%spring)
                eo%u_elastic = eo%u_elastic + sum(spring_energy(model%springs, gs%length))
                eo%p_diss = eo%p_diss + sum(model%springs%damping*gs%rate**2)
            end associate
        end if
        do e = 1, size(model%applied)
            associate (al => model%applied(e))
                call apply_applied_load(al, kin, t, loads)
                v = applied_vector(al, kin, t)
                if (al%kind == applied_couple) then
                    eo%p_applied = eo%p_applied + dot_product(v, kin%omega(:, al%body))
                else
                    p = matmul(kin%s(:, :, al%body), al%point)
                    pv = kin%v(:, al%body) + cross(kin%omega(:, al%body), p)
                    eo%p_applied = eo%p_applied + dot_product(v, pv)
                end if
            end associate
        end do
    end subroutine compute_loads

    !> Activation a(t) of every muscle: its activation history (Hill-type
    !! law) or table (eq 11); zero without either.
    pure function muscle_activations(model, t) result(act)
        type(model_t), intent(in) :: model   !! the model
        real(wp), intent(in) :: t            !! time [s]
        real(wp) :: act(size(model%muscles))
        integer :: e
        do e = 1, size(model%muscles)
            act(e) = muscle_activation(model, e, t)
        end do
    end function muscle_activations

    !> Activation a(t) of muscle e: its activation history (Hill-type law)
    !! or table (eq 11); zero without either.
    pure real(wp) function muscle_activation(model, e, t) result(act)
        type(model_t), intent(in) :: model   !! the model
        integer, intent(in) :: e             !! muscle number
        real(wp), intent(in) :: t            !! time [s]
        act = zero
        associate (m => model%muscles(e))
            if (m%law == muscle_hill) then
                if (m%history > 0) act = activation_value(model%activations(m%history), t)
            else if (m%activation > 0) then
                act = table_value(model%tables(m%activation), t)
            end if
        end associate
    end function muscle_activation

    !> Number of switching functions of the one-way elements.
    pure integer function switch_count(model) result(n)
        type(model_t), intent(in) :: model       !! the model
        integer :: e
        n = size(model%limits) + size(model%muscles)
        do e = 1, size(model%ligaments)
            if (model%ligaments(e)%l1 > zero) n = n + 1
        end do
    end function switch_count

    !> Switching functions whose sign changes mark where the one-way
    !! elements switch: a joint damper's coordinate crossing its neutral value
    !! (the damping switches on or off), a muscle's law (m1 d + m2 d' + a Fmax
    !! or the Hill force)
    !! crossing zero (tension starts or stops), a ligament with l1 > 0
    !! becoming taut. Families switched off give +1.
    pure subroutine switching_functions(model, t, kin, x, sw)
        type(model_t), intent(in) :: model       !! the model
        real(wp), intent(in) :: t                !! time [s]
        type(kinematics_t), intent(in) :: kin    !! kinematics at x
        real(wp), intent(in) :: x(:)             !! active coordinates [m, rad]
        real(wp), intent(out) :: sw(:)           !! (switch_count) the switching functions
        type(line_geometry_t) :: gl(size(model%ligaments)), gm(size(model%muscles))
        type(line_geometry_t) :: gseg(max_via + 1, size(model%muscles))
        real(wp) :: act(size(model%muscles))
        integer :: e, i
        sw = 1.0_wp
        i = 0
        do e = 1, size(model%limits)
            i = i + 1
            if (model%family_on(fam_limits)) sw(i) = x(model%limits(e)%dof) - model%limits(e)%xneutral
        end do
        if (model%family_on(fam_muscles)) then
            call muscle_geometries(kin, model%muscles, gm, gseg)
            act = muscle_activations(model, t)
            sw(i + 1:i + size(model%muscles)) = muscle_law_value(model%muscles, gm%length, gm%rate, act)
        end if
        i = i + size(model%muscles)
        if (model%family_on(fam_ligaments)) call line_geometries(kin, model%ligaments, gl)
        do e = 1, size(model%ligaments)
            if (model%ligaments(e)%l1 <= zero) cycle
            i = i + 1
            if (model%family_on(fam_ligaments)) sw(i) = gl(e)%length - model%ligaments(e)%length0
        end do
    end subroutine switching_functions

end module hn_forces
