!> Assembly of the applied loads of a model at one instant: gravity, force
!! elements and applied load tables, as body loads and generalized forces.
module hn_forces
    use hn_kinds, only: wp
    use hn_model, only: model_t
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t, loads_clear
    use hn_line_elements, only: line_geometry_t, line_geometry, apply_line_tension, spring_tension
    use hn_applied, only: apply_applied_load
    implicit none
    private

    public :: compute_loads

contains

    !> All applied loads at time t for the kinematic state kin.
    pure subroutine compute_loads(model, t, kin, loads)
        type(model_t), intent(in) :: model
        real(wp), intent(in) :: t
        type(kinematics_t), intent(in) :: kin
        type(body_loads_t), intent(inout) :: loads
        integer :: k, e
        type(line_geometry_t) :: g

        call loads_clear(loads)
        do k = 1, model%tree%nbody
            loads%force(:, k) = model%tree%mass(k)*model%gravity
        end do
        do e = 1, size(model%springs)
            associate (s => model%springs(e))
                call line_geometry(kin, s%body_a, s%point_a, s%body_b, s%point_b, g)
                call apply_line_tension(loads, kin, s%body_a, s%body_b, g, spring_tension(s, g%length, g%rate))
            end associate
        end do
        do e = 1, size(model%applied)
            call apply_applied_load(model%applied(e), kin, t, loads)
        end do
    end subroutine compute_loads

end module hn_forces
