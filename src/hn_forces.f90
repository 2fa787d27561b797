!> Assembly of the applied loads of a model at one instant: gravity, the
!! element families (discs, ligaments, muscles, joint-limit dampers,
!! springs), posture-holding generalized forces and applied load tables,
!! as body loads and generalized forces; plus each element's output.
module hn_forces
    use hn_kinds, only: wp, zero
    use hn_model, only: model_t, fam_discs, fam_ligaments, fam_muscles, fam_limits, fam_springs
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t, loads_clear
    use hn_line_elements, only: line_geometry_t, line_geometry, apply_line_tension, spring_tension, &
                                ligament_tension, muscle_tension
    use hn_discs, only: apply_disc
    use hn_joint_limits, only: limit_force
    use hn_applied, only: apply_applied_load
    use hn_tables, only: table_value
    implicit none
    private

    public :: element_output_t, element_output_allocate, compute_loads

    !> What each element does at the current instant.
    type :: element_output_t
        real(wp), allocatable :: disc(:, :)         !! (6, nd) resultants: shear x, y, axial, bending x, y, torque
        real(wp), allocatable :: ligament(:, :)     !! (2, nl) tension [N], length [m]
        real(wp), allocatable :: muscle(:, :)       !! (2, nm) tension [N], length [m]
        real(wp), allocatable :: limit(:)           !! (nlim) generalized force [N or N m]
        real(wp), allocatable :: spring(:)          !! (ns) tension [N]
    end type element_output_t

contains

    !> Size the element outputs of a model.
    pure subroutine element_output_allocate(model, eo)
        type(model_t), intent(in) :: model
        type(element_output_t), intent(out) :: eo
        allocate (eo%disc(6, size(model%discs)), eo%ligament(2, size(model%ligaments)))
        allocate (eo%muscle(2, size(model%muscles)), eo%limit(size(model%limits)))
        allocate (eo%spring(size(model%springs)))
        eo%disc = zero; eo%ligament = zero; eo%muscle = zero; eo%limit = zero; eo%spring = zero
    end subroutine element_output_allocate

    !> All applied loads at time t for the kinematic state kin (x, xd the
    !! active coordinates and rates the kinematics was computed from).
    pure subroutine compute_loads(model, t, kin, x, xd, loads, eo)
        type(model_t), intent(in) :: model
        real(wp), intent(in) :: t
        type(kinematics_t), intent(in) :: kin
        real(wp), intent(in) :: x(:), xd(:)
        type(body_loads_t), intent(inout) :: loads
        type(element_output_t), intent(inout) :: eo
        integer :: k, e
        real(wp) :: act, ten
        type(line_geometry_t) :: g

        call loads_clear(loads)
        do k = 1, model%tree%nbody
            loads%force(:, k) = model%tree%mass(k)*model%gravity
        end do
        loads%q = model%q_hold

        if (model%family_on(fam_discs)) then
            do e = 1, size(model%discs)
                call apply_disc(model%discs(e), kin, loads, eo%disc(:, e))
            end do
        end if
        if (model%family_on(fam_ligaments)) then
            do e = 1, size(model%ligaments)
                associate (l => model%ligaments(e))
                    call line_geometry(kin, l%body_a, l%point_a, l%body_b, l%point_b, g)
                    ten = ligament_tension(l, g%length)
                    call apply_line_tension(loads, kin, l%body_a, l%body_b, g, ten)
                    eo%ligament(:, e) = [ten, g%length]
                end associate
            end do
        end if
        if (model%family_on(fam_muscles)) then
            do e = 1, size(model%muscles)
                associate (m => model%muscles(e))
                    call line_geometry(kin, m%body_a, m%point_a, m%body_b, m%point_b, g)
                    act = zero
                    if (m%activation > 0) act = table_value(model%tables(m%activation), t)
                    ten = muscle_tension(m, g%length, g%rate, act)
                    call apply_line_tension(loads, kin, m%body_a, m%body_b, g, ten)
                    eo%muscle(:, e) = [ten, g%length]
                end associate
            end do
        end if
        if (model%family_on(fam_limits)) then
            do e = 1, size(model%limits)
                associate (lim => model%limits(e))
                    eo%limit(e) = limit_force(lim, x(lim%dof), xd(lim%dof))
                    loads%q(lim%dof) = loads%q(lim%dof) + eo%limit(e)
                end associate
            end do
        end if
        if (model%family_on(fam_springs)) then
            do e = 1, size(model%springs)
                associate (s => model%springs(e))
                    call line_geometry(kin, s%body_a, s%point_a, s%body_b, s%point_b, g)
                    eo%spring(e) = spring_tension(s, g%length, g%rate)
                    call apply_line_tension(loads, kin, s%body_a, s%body_b, g, eo%spring(e))
                end associate
            end do
        end if
        do e = 1, size(model%applied)
            call apply_applied_load(model%applied(e), kin, t, loads)
        end do
    end subroutine compute_loads

end module hn_forces
