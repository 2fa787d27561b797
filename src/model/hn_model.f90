!> The model: body tree, which coordinates are prescribed and how, gravity,
!! force elements and applied loads. Everything a dynamics evaluation reads.
module hn_model
    use hn_kinds, only: wp, zero, g_std, msglen
    use hn_tree, only: body_tree_t
    use hn_motion, only: motion_t
    use hn_tables, only: table_t
    use hn_muscle, only: activation_t
    use hn_line_elements, only: spring_t, ligament_t, muscle_t, set_neutral_lengths
    use hn_discs, only: disc_t, disc_set_reference
    use hn_joint_limits, only: joint_limit_t, joint_range_t
    use hn_applied, only: applied_load_t
    use hn_kinematics, only: kinematics_t, kinematics_allocate, partial_velocities
    use hn_linsolve, only: solver_gauss
    implicit none
    private

    public :: model_t, model_init, model_set_neutral, neutral_coordinates, family_count, family_items, family_items_text
    public :: scale_family

    integer, parameter, public :: max_family_items = 6   !! most properties a family has to scale

    !> Element families that can be switched on and off.
    integer, parameter, public :: fam_discs = 1, fam_ligaments = 2, fam_muscles = 3, &
                                  fam_limits = 4, fam_springs = 5, nfamilies = 5
    character(len=9), parameter, public :: family_name(nfamilies) = &
        [character(len=9) :: 'DISCS', 'LIGAMENTS', 'MUSCLES', 'LIMITS', 'SPRINGS']

    !> A complete mechanical model.
    type :: model_t
        character(len=80) :: title = ''
        type(body_tree_t) :: tree
        real(wp) :: gravity(3) = [zero, zero, -g_std]  !! gravitational acceleration in R [m/s^2]
        logical, allocatable :: prescribed(:)          !! (n) coordinate driven by `motion`
        type(motion_t), allocatable :: motion(:)       !! (n) its time history
        type(spring_t), allocatable :: springs(:)
        type(disc_t), allocatable :: discs(:)
        type(ligament_t), allocatable :: ligaments(:)
        type(muscle_t), allocatable :: muscles(:)
        type(joint_limit_t), allocatable :: limits(:)
        type(joint_range_t), allocatable :: ranges(:)  !! resistance beyond the range of motion (LIMITS family)
        type(applied_load_t), allocatable :: applied(:)
        type(table_t), allocatable :: tables(:)        !! activation tables referenced by muscles
        type(activation_t), allocatable :: activations(:)  !! activation histories of Hill-type muscles
        real(wp), allocatable :: q_hold(:)             !! (n) constant generalized forces (posture holding)
        logical :: family_on(nfamilies) = .true.       !! element families switched on
        integer :: solver = solver_gauss               !! solver of a_ij xddot = f
        character(len=8) :: jacobian = 'STRUCT'        !! Jacobian of the stiff integrators: STRUCT (from the elements) or FD
    end type model_t

contains

    !> Number of elements of family f in the model.
    pure integer function family_count(model, f) result(n)
        type(model_t), intent(in) :: model       !! the model
        integer, intent(in) :: f                 !! family (fam_discs ... fam_springs)
        select case (f)
        case (fam_discs); n = size(model%discs)
        case (fam_ligaments); n = size(model%ligaments)
        case (fam_muscles); n = size(model%muscles)
        case (fam_limits); n = size(model%limits)
        case (fam_springs); n = size(model%springs)
        case default; n = 0
        end select
    end function family_count

    !> Start a model on a built tree: nothing prescribed, no elements.
    pure subroutine model_init(model, tree)
        type(model_t), intent(out) :: model      !! the model, empty
        type(body_tree_t), intent(in) :: tree    !! the built body tree
        model%tree = tree
        allocate (model%prescribed(tree%ndof), model%motion(tree%ndof), model%q_hold(tree%ndof))
        model%prescribed = .false.
        model%q_hold = zero
        allocate (model%springs(0), model%discs(0), model%ligaments(0), model%muscles(0))
        allocate (model%limits(0), model%applied(0), model%tables(0), model%activations(0), &
                  model%ranges(0))
    end subroutine model_init

    !> Active coordinates of the neutral configuration (every coordinate at
    !! its reference value).
    pure function neutral_coordinates(model) result(x)
        type(model_t), intent(in) :: model       !! the model
        real(wp) :: x(model%tree%ndof)
        integer :: j
        do j = 1, model%tree%ndof
            x(j) = model%tree%q_ref(model%tree%dof_local(j), model%tree%dof_body(j))
        end do
    end function neutral_coordinates

    !> Measure the neutral configuration: disc plate frames and offsets,
    !! and the free lengths of ligaments and muscles not given explicitly.
    pure subroutine model_set_neutral(model)
        type(model_t), intent(inout) :: model    !! the model; out: disc references and free lengths set
        type(kinematics_t) :: kin
        real(wp) :: x0(model%tree%ndof)
        integer :: e
        x0 = neutral_coordinates(model)
        call kinematics_allocate(model%tree, kin)
        call partial_velocities(model%tree, x0, 0*x0, kin)
        do e = 1, size(model%discs)
            call disc_set_reference(model%discs(e), kin)
        end do
        call set_neutral_lengths(kin, model%ligaments)
        call set_neutral_lengths(kin, model%muscles)
        call set_neutral_lengths(kin, model%springs)
    end subroutine model_set_neutral

    !> Properties of a family that a FAMILY parameter may scale.
    pure function family_items(f) result(items)
        integer, intent(in) :: f                 !! family (fam_discs ... fam_springs)
        character(len=10) :: items(max_family_items)
        items = ''
        select case (f)
        case (fam_discs); items = [character(len=10) :: 'E', 'VISCOUS', 'G', 'VAXIAL', 'VBEND', 'ETENSION']
        case (fam_ligaments); items(1:2) = [character(len=10) :: 'L1', 'L2']
        case (fam_muscles); items(1:3) = [character(len=10) :: 'M1', 'M2', 'F0']
        case (fam_limits); items(1:3) = [character(len=10) :: 'C0', 'C1', 'ROMK']
        case (fam_springs); items(1:2) = [character(len=10) :: 'K', 'C']
        end select
    end function family_items

    !> The properties of a family that a FAMILY parameter may scale, as text: "A, B or C".
    pure function family_items_text(f) result(s)
        integer, intent(in) :: f                 !! family (fam_discs ... fam_springs)
        character(len=:), allocatable :: s
        character(len=10) :: items(max_family_items)
        integer :: k, n
        items = family_items(f)
        n = count(len_trim(items) > 0)
        s = trim(items(1))
        do k = 2, n
            if (k == n) then
                s = s//' or '//trim(items(k))
            else
                s = s//', '//trim(items(k))
            end if
        end do
    end function family_items_text

    !> Multiply one property of every element of a family by `factor`.
    pure subroutine scale_family(model, f, item, factor)
        type(model_t), intent(inout) :: model    !! the model
        integer, intent(in) :: f                 !! family (fam_discs ... fam_springs)
        character(len=*), intent(in) :: item     !! property, one of family_items(f)
        real(wp), intent(in) :: factor           !! the factor
        select case (f)
        case (fam_discs)
            where (model%discs%d2b < zero) model%discs%d2b = model%discs%d2   ! d2b not given: d2 from here on
            select case (item)
            case ('E'); model%discs%d1 = factor*model%discs%d1
            case ('VISCOUS')     ! every mode's damping
                model%discs%d2 = factor*model%discs%d2
                model%discs%d2b = factor*model%discs%d2b
            case ('VAXIAL'); model%discs%d2 = factor*model%discs%d2     ! axial damping (eq 1)
            case ('VBEND'); model%discs%d2b = factor*model%discs%d2b    ! shear, bending, torsion damping
            case ('G'); model%discs%g = factor*model%discs%g
            case ('ETENSION'); model%discs%ft = factor*model%discs%ft   ! axial stiffness in tension / d1's
            end select
        case (fam_ligaments)
            select case (item)
            case ('L1'); model%ligaments%l1 = factor*model%ligaments%l1
            case ('L2'); model%ligaments%l2 = factor*model%ligaments%l2
            end select
        case (fam_muscles)
            select case (item)
            case ('M1'); model%muscles%m1 = factor*model%muscles%m1
            case ('M2')      ! the damping of either law: m2 (eq 11) and the Hill damping
                model%muscles%m2 = factor*model%muscles%m2
                model%muscles%hill%damping = factor*model%muscles%hill%damping
            case ('F0')      ! Hill-type muscles: F0 and the damping that is proportional to it
                model%muscles%hill%f0 = factor*model%muscles%hill%f0
                model%muscles%hill%damping = factor*model%muscles%hill%damping
            end select
        case (fam_limits)
            select case (item)
            case ('C0'); model%limits%c0 = factor*model%limits%c0
            case ('C1'); model%limits%c1 = factor*model%limits%c1
            case ('ROMK'); model%ranges%k = factor*model%ranges%k
            end select
        case (fam_springs)
            select case (item)
            case ('K'); model%springs%stiffness = factor*model%springs%stiffness
            case ('C'); model%springs%damping = factor*model%springs%damping
            end select
        end select
    end subroutine scale_family

end module hn_model
