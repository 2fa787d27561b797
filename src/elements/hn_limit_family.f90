!> The LIMITS family: one-way joint-limit dampers (eqs 12-13) and the
!! resistance beyond the physiological range of motion (ROM cards), both
!! from hn_joint_limits, behind the element-family interface. Output per
!! damper: its generalized force [N or N m].
module hn_limit_family
    use hn_kinds, only: wp, zero
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t
    use hn_tree, only: body_tree_t
    use hn_joint_limits, only: joint_limit_t, joint_range_t, limit_force, range_moment, range_energy
    use hn_element_family, only: element_family_t, family_work_t, family_channel_t, element_table_t, max_family_items, item_len, &
                                 warning_len, fd_rel, fd_abs_length, fd_abs_rate, check_range
    implicit none
    private

    public :: limit_family_t, limits_of, ranges_of

    real(wp), parameter :: ref_limit_c1 = 100.0_wp        !! N m s/rad per rad (reference/parameters.md)
    character(len=2), parameter :: coord_names(6) = ['TX', 'TY', 'TZ', 'RX', 'RY', 'RZ']

    !> The joint-limit dampers and ranges of motion of a model.
    type, extends(element_family_t) :: limit_family_t
        type(joint_limit_t), allocatable :: items(:)    !! dampers (LIMIT cards)
        type(joint_range_t), allocatable :: ranges(:)   !! ranges of motion (ROM cards)
    contains
        procedure :: count => limit_count
        procedure :: ncomp => limit_ncomp
        procedure :: set_neutral => limit_neutral
        procedure :: add_loads => limit_loads
        procedure :: add_tangent => limit_tangent
        procedure :: switch_count => limit_switch_count
        procedure :: switching => limit_switching
        procedure :: channels => limit_channels
        procedure :: result_table => limit_table
        procedure :: plausibility => limit_plausibility
        procedure :: scale_items => limit_items
        procedure :: scale => limit_scale
        procedure :: stiffen => limit_stiffen
    end type limit_family_t

contains

    !> Number of dampers (the ranges are counted apart: size(ranges)).
    pure integer function limit_count(this) result(n)
        class(limit_family_t), intent(in) :: this   !! the family
        n = 0
        if (allocated(this%items)) n = size(this%items)
    end function limit_count

    !> Output rows per damper: its generalized force.
    pure integer function limit_ncomp(this) result(n)
        class(limit_family_t), intent(in) :: this   !! the family
        n = 1
    end function limit_ncomp

    !> Nothing to set up: the neutral values come from the cards.
    pure subroutine limit_neutral(this, kin)
        class(limit_family_t), intent(inout) :: this   !! the family (unchanged)
        type(kinematics_t), intent(in) :: kin          !! kinematics of the neutral configuration (unused)
    end subroutine limit_neutral

    !> Damper forces and range moments on their coordinates; dissipated power, stored energy.
    pure subroutine limit_loads(this, t, kin, x, xd, loads, out, work, u_elastic, p_diss, p_muscle)
        class(limit_family_t), intent(in) :: this     !! the family
        real(wp), intent(in) :: t                     !! time [s]
        type(kinematics_t), intent(in) :: kin         !! kinematics at (x, xd)
        real(wp), intent(in) :: x(:)                  !! active coordinates [m, rad]
        real(wp), intent(in) :: xd(:)                 !! their rates [m/s, rad/s]
        type(body_loads_t), intent(inout) :: loads    !! generalized forces, the family's added
        real(wp), intent(inout) :: out(:, :)          !! (1, nlim) damper forces [N or N m]
        type(family_work_t), intent(inout) :: work    !! scratch (line geometry)
        real(wp), intent(inout) :: u_elastic          !! stored energy [J]
        real(wp), intent(inout) :: p_diss             !! dissipated power [W]
        real(wp), intent(inout) :: p_muscle           !! muscle power [W] (none here)
        integer :: e
        do e = 1, size(this%items)
            associate (lim => this%items(e))
                out(1, e) = limit_force(lim, x(lim%dof), xd(lim%dof))
                loads%q(lim%dof) = loads%q(lim%dof) + out(1, e)
                p_diss = p_diss - out(1, e)*xd(lim%dof)
            end associate
        end do
        do e = 1, size(this%ranges)
            associate (r => this%ranges(e))
                loads%q(r%dof) = loads%q(r%dof) + range_moment(r, x(r%dof))
                u_elastic = u_elastic + range_energy(r, x(r%dof))
            end associate
        end do
    end subroutine limit_loads

    !> Dampers: -dQ/dx and -dQ/dxdot of their laws on their coordinates;
    !! ranges (elastic beyond the range): K_jj -= dQ/dx.
    pure subroutine limit_tangent(this, tree, kin, t, x, xd, kgen, cgen, cols, sgn, idx, b, bd)
        class(limit_family_t), intent(in) :: this     !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree (unused)
        type(kinematics_t), intent(in) :: kin         !! kinematics (unused)
        real(wp), intent(in) :: t                     !! time [s]
        real(wp), intent(in) :: x(:)                  !! active coordinates
        real(wp), intent(in) :: xd(:)                 !! their rates
        real(wp), intent(inout) :: kgen(:, :)         !! generalized stiffness, the family's added
        real(wp), intent(inout) :: cgen(:, :)         !! generalized damping, the family's added
        integer, intent(out) :: cols(:)               !! scratch (unused)
        integer, intent(out) :: sgn(:)                !! scratch (unused)
        integer, intent(out) :: idx(:)                !! scratch (unused)
        real(wp), intent(out) :: b(:)                 !! scratch (unused)
        real(wp), intent(out) :: bd(:, :)             !! scratch (unused)
        real(wp) :: dx, dv
        integer :: e, j
        cols = 0; sgn = 0; idx = 0; b = zero; bd = zero
        do e = 1, size(this%items)
            associate (lim => this%items(e))
                j = lim%dof
                dx = max(fd_rel*abs(x(j)), fd_abs_length)
                dv = max(fd_rel*abs(xd(j)), fd_abs_rate)
                kgen(j, j) = kgen(j, j) - (limit_force(lim, x(j) + dx, xd(j)) - limit_force(lim, x(j) - dx, xd(j)))/(2*dx)
                cgen(j, j) = cgen(j, j) - (limit_force(lim, x(j), xd(j) + dv) - limit_force(lim, x(j), xd(j) - dv))/(2*dv)
            end associate
        end do
        do e = 1, size(this%ranges)
            associate (r => this%ranges(e))
                j = r%dof
                dx = max(fd_rel*abs(x(j)), fd_abs_length)
                kgen(j, j) = kgen(j, j) - (range_moment(r, x(j) + dx) - range_moment(r, x(j) - dx))/(2*dx)
            end associate
        end do
    end subroutine limit_tangent

    !> One switching function per damper (its coordinate crossing the neutral value).
    pure integer function limit_switch_count(this) result(n)
        class(limit_family_t), intent(in) :: this   !! the family
        n = size(this%items)
    end function limit_switch_count

    !> Coordinate less neutral value of every damper: the damping switches on or off.
    pure subroutine limit_switching(this, t, kin, x, sw)
        class(limit_family_t), intent(in) :: this     !! the family
        real(wp), intent(in) :: t                     !! time [s]
        type(kinematics_t), intent(in) :: kin         !! kinematics at x (unused)
        real(wp), intent(in) :: x(:)                  !! active coordinates
        real(wp), intent(out) :: sw(:)                !! (switch_count) the switching functions
        integer :: e
        do e = 1, size(this%items)
            sw(e) = x(this%items(e)%dof) - this%items(e)%xneutral
        end do
    end subroutine limit_switching

    !> One channel per damper: L_body_coordinate.
    pure function limit_channels(this, tree) result(c)
        class(limit_family_t), intent(in) :: this     !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree (body names)
        type(family_channel_t), allocatable :: c(:)
        integer :: e, k, m
        allocate (c(size(this%items)))
        do e = 1, size(this%items)
            k = this%items(e)%body
            m = this%items(e)%local
            c(e) = family_channel_t('L_'//trim(tree%name(k))//'_'//coord_names(m), merge('N  ', 'N m', m <= 3), &
                                    'JOINT LIMITS', e, 1)
        end do
    end function limit_channels

    !> No table in the result file (the dampers act on coordinates, not between points).
    pure function limit_table(this) result(tab)
        class(limit_family_t), intent(in) :: this     !! the family
        type(element_table_t) :: tab
        tab%group = ''
    end function limit_table

    !> Rotational dampers whose ramp C1 is far from the reference model's.
    pure subroutine limit_plausibility(this, tree, warnings)
        class(limit_family_t), intent(in) :: this     !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree
        character(len=warning_len), allocatable, intent(inout) :: warnings(:)  !! warnings, the family's added
        integer :: e
        do e = 1, size(this%items)
            if (this%items(e)%local > 3) call check_range('joint-limit damper on '// &
                trim(tree%name(this%items(e)%body))//' ramp C1', this%items(e)%c1, ref_limit_c1, 'N m s/rad/rad', &
                warnings)
        end do
    end subroutine limit_plausibility

    !> C0, C1, ROMK.
    pure subroutine limit_items(this, items)
        class(limit_family_t), intent(in) :: this     !! the family
        character(len=item_len), intent(out) :: items(max_family_items)   !! the properties
        items = ''
        items(1:3) = [character(len=item_len) :: 'C0', 'C1', 'ROMK']
    end subroutine limit_items

    !> Scale C0 or C1 of every damper, or K of every range.
    pure subroutine limit_scale(this, item, factor)
        class(limit_family_t), intent(inout) :: this   !! the family
        character(len=*), intent(in) :: item           !! C0, C1 or ROMK
        real(wp), intent(in) :: factor                 !! the factor
        select case (item)
        case ('C0'); this%items%c0 = factor*this%items%c0
        case ('C1'); this%items%c1 = factor*this%items%c1
        case ('ROMK'); this%ranges%k = factor*this%ranges%k
        end select
    end subroutine limit_scale

    !> STIFFEN leaves the dampers and ranges as they are (they are not stiffnesses of the element laws).
    pure subroutine limit_stiffen(this, factor)
        class(limit_family_t), intent(inout) :: this   !! the family (unchanged)
        real(wp), intent(in) :: factor                 !! the factor (unused)
    end subroutine limit_stiffen

    !> The joint-limit dampers of a model's family slot (a copy; none when the slot holds another family).
    pure function limits_of(fam) result(items)
        class(element_family_t), intent(in) :: fam   !! the slot's family
        type(joint_limit_t), allocatable :: items(:)
        select type (fam)
        type is (limit_family_t)
            items = fam%items
        class default
            allocate (items(0))
        end select
    end function limits_of

    !> The ranges of motion of a model's family slot (a copy; none when the slot holds another family).
    pure function ranges_of(fam) result(items)
        class(element_family_t), intent(in) :: fam   !! the slot's family
        type(joint_range_t), allocatable :: items(:)
        select type (fam)
        type is (limit_family_t)
            items = fam%ranges
        class default
            allocate (items(0))
        end select
    end function ranges_of

end module hn_limit_family
