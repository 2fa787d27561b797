!> Assembly of the applied loads of a model at one instant: gravity, the
!! element families (each family's `add_loads`, once per family, in the
!! registry's order), posture-holding generalized forces (times their
!! release factor s(t), hn_model's hold_factor) and applied load tables, as
!! body loads and generalized forces; plus each element's output.
module hn_forces
    use hn_kinds, only: wp, zero, one
    use hn_model, only: model_t, hold_factor
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t, loads_clear
    use hn_applied, only: apply_applied_load, applied_vector, applied_couple
    use hn_rotation, only: cross
    use hn_element_family, only: family_work_t, family_energy_t
    use hn_line_elements, only: max_via
    implicit none
    private

    public :: element_output_t, family_values_t, element_output_allocate, compute_loads, switch_count, &
              switching_functions

    !> The outputs of one family's elements.
    type :: family_values_t
        real(wp), allocatable :: v(:, :)            !! (ncomp, count) what the family's add_loads returns
        type(family_work_t) :: work                 !! its scratch, kept between evaluations
    end type family_values_t

    !> What each element does at the current instant.
    type :: element_output_t
        !> per family: discs (6, nd) resultants shear x, y, axial, bending x, y, torque; ligaments (2, nl)
        !! tension [N], length [m]; muscles (3, nm) tension [N], length [m], activation; limits (1, nlim)
        !! generalized force [N or N m]; springs (1, ns) tension [N]
        type(family_values_t), allocatable :: fam(:)
        !> energy stored in discs, ligaments, springs, contacts [J]; power dissipated by discs, springs,
        !! joint dampers, contacts and absorbed by the muscles [W]
        type(family_energy_t) :: energy
        !> power of the applied force and couple tables, and of the release of the holding forces,
        !! (s - 1) q_hold . xdot (hn_dynamics' energy_terms) [W]
        real(wp) :: p_applied = zero
        real(wp) :: hold_factor = one               !! the release factor s(t) on q_hold
    end type element_output_t

contains

    !> Size the element outputs of a model.
    pure subroutine element_output_allocate(model, eo)
        type(model_t), intent(in) :: model       !! the model
        type(element_output_t), intent(out) :: eo !! outputs sized for its elements, zero
        integer :: f
        allocate (eo%fam(size(model%family)))
        do f = 1, size(model%family)
            associate (fam => model%family(f)%f)
                allocate (eo%fam(f)%v(fam%ncomp(), fam%count()))
                allocate (eo%fam(f)%work%g(fam%count()), eo%fam(f)%work%seg(max_via + 1, fam%count()))
            end associate
            eo%fam(f)%v = zero
        end do
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
        integer :: k, e, f
        real(wp) :: v(3), p(3), pv(3)

        call loads_clear(loads)
        eo%energy = family_energy_t(); eo%p_applied = zero
        do k = 1, model%tree%nbody
            loads%force(:, k) = model%tree%mass(k)*model%gravity
        end do
        eo%hold_factor = hold_factor(model, t)
        loads%q = eo%hold_factor*model%q_hold
        if (eo%hold_factor /= one) eo%p_applied = (eo%hold_factor - one)*dot_product(model%q_hold, xd)

        do f = 1, size(model%family)
            if (model%family_on(f)) call model%family(f)%f%add_loads(t, kin, x, xd, loads, eo%fam(f)%v, &
                                                                     eo%fam(f)%work, eo%energy)
        end do
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

    !> Number of switching functions of the one-way elements.
    pure integer function switch_count(model) result(n)
        type(model_t), intent(in) :: model       !! the model
        integer :: f
        n = 0
        do f = 1, size(model%family)
            n = n + model%family(f)%f%switch_count()
        end do
    end function switch_count

    !> Switching functions whose sign changes mark where the one-way
    !! elements switch, family by family in the registry's order: a ligament
    !! with l1 > 0 becoming taut, a muscle's law (m1 d + m2 d' + a Fmax or
    !! the Hill force) crossing zero (tension starts or stops), a joint
    !! damper's coordinate crossing its neutral value (the damping switches on
    !! or off). Families switched off give +1.
    pure subroutine switching_functions(model, t, kin, x, sw)
        type(model_t), intent(in) :: model       !! the model
        real(wp), intent(in) :: t                !! time [s]
        type(kinematics_t), intent(in) :: kin    !! kinematics at x
        real(wp), intent(in) :: x(:)             !! active coordinates [m, rad]
        real(wp), intent(out) :: sw(:)           !! (switch_count) the switching functions
        integer :: f, i, n
        sw = 1.0_wp
        i = 0
        do f = 1, size(model%family)
            n = model%family(f)%f%switch_count()
            if (model%family_on(f) .and. n > 0) call model%family(f)%f%switching(t, kin, x, sw(i + 1:i + n))
            i = i + n
        end do
    end subroutine switching_functions

end module hn_forces
