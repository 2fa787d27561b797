!> The LIMITS family: one-way joint-limit dampers (eqs 12-13) and the
!! resistance beyond the physiological range of motion (ROM cards), both
!! from hn_joint_limits, behind the element-family interface. Output per
!! damper: its generalized force [N or N m]. The family reads its LIMIT and
!! ROM cards; those on a locked or merged coordinate are dropped, with a
!! scene note. Its run monitor watches the joints' excess beyond their
!! ranges of motion (a warning past range_margin), and a settled start
!! (HOLD PRESTRAIN) whose neutrals leave their ranges.
module hn_limit_family
    use hn_kinds, only: wp, zero, deg
    use hn_deck_reader, only: deck_reader_t
    use hn_element_cards, only: card_context_t, active_coordinate, unit_of, unit_factor, unit_limit, &
                                big_modulus, coord_names
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t
    use hn_tree, only: body_tree_t
    use hn_joint_limits, only: joint_limit_t, joint_range_t, limit_force, range_moment, range_energy, range_excess, &
                               range_warnings, range_margin
    use hn_element_family, only: element_family_t, family_work_t, family_channel_t, element_table_t, max_family_items, item_len, &
                                 warning_len, fd_rel, fd_abs_length, fd_abs_rate, check_range
    use hn_family_registration, only: family_registration_t
    use hn_element_cards, only: family_card_t, unique_coordinate
    use hn_element_family, only: family_slot_t
    use hn_element_family, only: family_energy_t, tangent_work_t
    implicit none
    private

    public :: limit_family_t, limits_of, ranges_of
    public :: limit_registration

    real(wp), parameter :: ref_limit_c1 = 100.0_wp        !! N m s/rad per rad (reference/parameters.md)

    !> The joint-limit dampers and ranges of motion of a model.
    type, extends(element_family_t) :: limit_family_t
        type(joint_limit_t), allocatable :: items(:)    !! dampers (LIMIT cards)
        type(joint_range_t), allocatable :: ranges(:)   !! ranges of motion (ROM cards)
        integer :: nread(2) = 0     !! dampers and ranges read from the deck so far (room for every card until end_cards)
        integer :: ndropped = 0     !! LIMIT and ROM cards dropped: on locked or merged coordinates
    contains
        procedure :: read_card => limit_read_card
        procedure :: end_cards => limit_end_cards
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
        procedure :: monitor_count => range_count
        procedure :: monitor => range_monitor
        procedure :: monitor_report => range_report
        procedure :: neutral_warning => range_neutral_warning
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
    pure subroutine limit_loads(this, t, kin, x, xd, loads, out, work, energy)
        class(limit_family_t), intent(in) :: this     !! the family
        real(wp), intent(in) :: t                     !! time [s]
        type(kinematics_t), intent(in) :: kin         !! kinematics at (x, xd)
        real(wp), intent(in) :: x(:)                  !! active coordinates [m, rad]
        real(wp), intent(in) :: xd(:)                 !! their rates [m/s, rad/s]
        type(body_loads_t), intent(inout) :: loads    !! generalized forces, the family's added
        real(wp), intent(inout) :: out(:, :)          !! (1, nlim) damper forces [N or N m]
        type(family_work_t), intent(inout) :: work    !! scratch (line geometry)
        type(family_energy_t), intent(inout) :: energy !! energy stored, power dissipated and absorbed, the family's added
        integer :: e
        do e = 1, size(this%items)
            associate (lim => this%items(e))
                out(1, e) = limit_force(lim, x(lim%dof), xd(lim%dof))
                loads%q(lim%dof) = loads%q(lim%dof) + out(1, e)
                energy%p_diss = energy%p_diss - out(1, e)*xd(lim%dof)
            end associate
        end do
        do e = 1, size(this%ranges)
            associate (r => this%ranges(e))
                loads%q(r%dof) = loads%q(r%dof) + range_moment(r, x(r%dof))
                energy%u_elastic = energy%u_elastic + range_energy(r, x(r%dof))
            end associate
        end do
    end subroutine limit_loads

    !> The dampers: -dQ/dx and -dQ/dxdot of their laws on their coordinates;
    !! ranges (elastic beyond the range): K_jj -= dQ/dx.
    pure subroutine limit_tangent(this, tree, kin, t, x, xd, kgen, cgen, tw)
        class(limit_family_t), intent(in) :: this     !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree (unused)
        type(kinematics_t), intent(in) :: kin         !! kinematics (unused)
        real(wp), intent(in) :: t                     !! time [s]
        real(wp), intent(in) :: x(:)                  !! active coordinates
        real(wp), intent(in) :: xd(:)                 !! their rates
        real(wp), intent(inout) :: kgen(:, :)         !! generalized stiffness, the family's added
        real(wp), intent(inout) :: cgen(:, :)         !! generalized damping, the family's added
        type(tangent_work_t), intent(inout) :: tw     !! scratch sized for the coordinates
        real(wp) :: dx, dv
        integer :: e, j
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

    !> C0, C1, ROMK, ROMT0.
    pure subroutine limit_items(this, items)
        class(limit_family_t), intent(in) :: this     !! the family
        character(len=item_len), intent(out) :: items(max_family_items)   !! the properties
        items = ''
        items(1:4) = [character(len=item_len) :: 'C0', 'C1', 'ROMK', 'ROMT0']
    end subroutine limit_items

    !> Scale C0 or C1 of every damper, or K or t0 of every range.
    pure subroutine limit_scale(this, item, factor)
        class(limit_family_t), intent(inout) :: this   !! the family
        character(len=*), intent(in) :: item           !! C0, C1, ROMK or ROMT0
        real(wp), intent(in) :: factor                 !! the factor
        select case (item)
        case ('C0'); this%items%c0 = factor*this%items%c0
        case ('C1'); this%items%c1 = factor*this%items%c1
        case ('ROMK'); this%ranges%k = factor*this%ranges%k
        case ('ROMT0'); this%ranges%t0 = factor*this%ranges%t0
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

    !> The run monitor watches one quantity per range of motion.
    pure integer function range_count(this) result(n)
        class(limit_family_t), intent(in) :: this   !! the family
        n = size(this%ranges)
    end function range_count

    !> |excess| of each joint beyond its range of motion at coordinates x [rad].
    pure subroutine range_monitor(this, x, excess)
        class(limit_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: x(:)                !! active coordinates [m, rad]
        real(wp), intent(out) :: excess(:)          !! (ranges) |excess| of each [rad]
        integer :: k
        do k = 1, size(this%ranges)
            excess(k) = abs(range_excess(this%ranges(k), x(this%ranges(k)%dof)))
        end do
    end subroutine range_monitor

    !> Joints past their physiological range by more than range_margin: one
    !! line each for the listing, and summed up in the run's warning.
    pure subroutine range_report(this, peak, tpeak, lines, summary)
        class(limit_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: peak(:)             !! (ranges) largest |excess| of each [rad]
        real(wp), intent(in) :: tpeak(:)            !! (ranges) when [s]
        character(len=warning_len), allocatable, intent(out) :: lines(:)   !! one line per joint past range and margin
        character(len=:), allocatable, intent(out) :: summary              !! the run's warning ('': none)
        character(len=400) :: w
        integer :: k
        lines = range_warnings(this%ranges, peak, tpeak, range_margin)
        summary = ''
        if (size(lines) == 0) return
        k = count(peak(1:maxloc(peak, dim=1)) > range_margin)
        write (w, '(a,i0,2a)') 'WARNING: ', size(lines), ' joint rotation(s) past the physiological '// &
            'range plus margin; largest: ', trim(lines(k)(16:))
        summary = trim(w)
    end subroutine range_report

    !> HOLD PRESTRAIN: the joints whose settled neutral xr + dx is out of
    !! their range of motion ('' when none).
    pure function range_neutral_warning(this, xr, dx) result(w)
        class(limit_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: xr(:)               !! neutral active coordinates [m, rad]
        real(wp), intent(in) :: dx(:)               !! the settled displacement [m, rad]
        character(len=:), allocatable :: w
        character(len=400) :: line
        real(wp) :: e, excess
        integer :: k, nout, worst
        nout = 0
        worst = 0
        excess = zero
        associate (rom => this%ranges)
            do k = 1, size(rom)
                e = max(xr(rom(k)%dof) + dx(rom(k)%dof) - rom(k)%xmax, rom(k)%xmin - xr(rom(k)%dof) - dx(rom(k)%dof))
                if (e <= zero) cycle
                nout = nout + 1
                if (e > excess) then
                    excess = e
                    worst = k
                end if
            end do
            w = ''
            if (nout == 0) return
            write (line, '(a,i0,3a,f8.2,a)') 'WARNING: HOLD PRESTRAIN moves ', nout, &
                ' joint neutral(s) out of their range of motion; largest: ', trim(rom(worst)%label), ' by ', &
                excess/deg, ' deg (the start load is not a preload of the joints: held by the muscles, it is '// &
                'HOLD POSTURE''s)'
        end associate
        w = trim(line)
    end function range_neutral_warning

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

    !> A LIMIT or ROM card: a damper or a range of motion, dropped on a
    !! locked or merged coordinate.
    subroutine limit_read_card(this, rd, ctx, i, key)
        class(limit_family_t), intent(inout) :: this   !! the family; out: the card's damper or range added
        type(deck_reader_t), intent(inout) :: rd       !! the deck: card images, located field access, the first error
        type(card_context_t), intent(inout) :: ctx     !! the deck's bodies and the reduced tree
        integer, intent(in) :: i                       !! the card's first deck line
        character(len=*), intent(in) :: key            !! the card name (LIMIT or ROM)
        ! room for every LIMIT and ROM card, trimmed by end_cards (appending one by one is quadratic)
        if (this%nread(1) == 0 .and. size(this%items) < ctx%ncards('LIMIT')) then
            deallocate (this%items)
            allocate (this%items(ctx%ncards('LIMIT')))
        end if
        if (this%nread(2) == 0 .and. size(this%ranges) < ctx%ncards('ROM')) then
            deallocate (this%ranges)
            allocate (this%ranges(ctx%ncards('ROM')))
        end if
        call joint_card(rd, i, ctx, this)
    end subroutine limit_read_card

    !> The dampers and ranges read: no room left over; a scene note of those dropped.
    subroutine limit_end_cards(this, rd, ctx)
        class(limit_family_t), intent(inout) :: this   !! the family; out: items and ranges trimmed
        type(deck_reader_t), intent(inout) :: rd       !! the deck (unused)
        type(card_context_t), intent(inout) :: ctx     !! out: the note of the dampers dropped
        character(len=100) :: note
        this%items = this%items(1:this%nread(1))
        this%ranges = this%ranges(1:this%nread(2))
        if (this%ndropped > 0) then
            write (note, '(i0,a)') this%ndropped, ' JOINT-LIMIT DAMPERS DROPPED: ON LOCKED OR MERGED COORDINATES'
            call ctx%add_note(note)
        end if
    end subroutine limit_end_cards

    !> A LIMIT card (one-way joint-limit damper) or a ROM card (resistance
    !! beyond the physiological range: rotation, range (deg), stiffness at the
    !! edge K [N m/rad], excess t0 [deg] over which it grows e-fold); dropped
    !! on a locked or merged coordinate.
    subroutine joint_card(rd, i, ctx, jf)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        type(card_context_t), intent(in) :: ctx  !! the deck's bodies (names, where each went) and the reduced tree
        class(limit_family_t), intent(inout) :: jf   !! the dampers and ranges read so far (nread), those dropped (ndropped)
        type(joint_limit_t) :: lim
        type(joint_range_t) :: r
        integer :: kb, m, j
        logical :: merged
        ! a body absorbed by MERGE or a locked coordinate: the element would do nothing
        call active_coordinate(rd, i, ctx%tree, ctx%bnames, ctx%bmap, kb, m, j, .true., merged)
        if (rd%failed()) return
        if (merged .or. j == 0) then
            jf%ndropped = jf%ndropped + 1
            return
        end if
        if (rd%key(i) == 'LIMIT') then
            lim = joint_limit_t()
            lim%body = kb; lim%local = m; lim%dof = j
            call rd%real(i, 3, 'lower limit', unit_of(m), lim%xmin, -unit_limit(m), unit_limit(m))
            call rd%real(i, 4, 'upper limit', unit_of(m), lim%xmax, -unit_limit(m), unit_limit(m))
            if (.not. rd%failed() .and. .not. (lim%xmax > lim%xmin)) then
                call rd%fail(rd%context(i, 4, 'upper limit')//': found '// &
                             trim(rd%raw(i, 4))//'; expected a value above the lower limit '//trim(rd%raw(i, 3)))
                return
            end if
            call rd%real(i, 5, 'damping C0', 'N s/m or N m s/rad', lim%c0, zero, big_modulus)
            call rd%real(i, 6, 'damping ramp C1', 'per m or per rad of excess', lim%c1, zero, big_modulus)
            call rd%real(i, 7, 'neutral value', unit_of(m), lim%xneutral, lim%xmin, lim%xmax, &
                         default=max(lim%xmin, min(lim%xmax, ctx%tree%q_ref(m, kb)/unit_factor(m))))
            lim%xmin = lim%xmin*unit_factor(m)
            lim%xmax = lim%xmax*unit_factor(m)
            lim%xneutral = lim%xneutral*unit_factor(m)
            if (rd%failed()) return
            jf%nread(1) = jf%nread(1) + 1; jf%items(jf%nread(1)) = lim
            return
        end if
        if (m <= 3) then
            call rd%fail(rd%context(i, 2, 'coordinate')//': found '//coord_names(m)//'; expected a rotation '// &
                         '(RX, RY or RZ): ROM cards hold joint rotations')
            return
        end if
        r%dof = j
        r%label = trim(ctx%tree%name(kb))//' '//coord_names(m)
        call rd%real(i, 3, 'lower end of range', 'deg', r%xmin, -180.0_wp, 180.0_wp)
        call rd%real(i, 4, 'upper end of range', 'deg', r%xmax, -180.0_wp, 180.0_wp)
        if (.not. rd%failed() .and. .not. (r%xmax > r%xmin)) then
            call rd%fail(rd%context(i, 4, 'upper end of range')//': found '//trim(rd%raw(i, 4))// &
                         '; expected a value above the lower end '//trim(rd%raw(i, 3)))
            return
        end if
        call rd%real(i, 5, 'stiffness at the edge K', 'N m/rad', r%k, zero, big_modulus)
        call rd%real(i, 6, 'e-fold excess t0', 'deg', r%t0, 0.01_wp, 90.0_wp, default=5.0_wp)
        if (rd%failed()) return
        r%xmin = r%xmin*deg; r%xmax = r%xmax*deg; r%t0 = r%t0*deg
        jf%nread(2) = jf%nread(2) + 1; jf%ranges(jf%nread(2)) = r
    end subroutine joint_card

    !> The registry's entry of the limits: name LIMITS, its cards LIMIT and ROM (one
    !! per body and coordinate), and the family with no elements.
    pure function limit_registration() result(r)
        type(family_registration_t) :: r
        r = family_registration_t('LIMITS', [ &
            family_card_t('LIMIT', 0, 0, unique=unique_coordinate, coordinate=.true.), &
            family_card_t('ROM', 0, 0, unique=unique_coordinate, coordinate=.true.)], limit_empty)
    end function limit_registration

    !> A family of limits with no elements (its arrays allocated with size 0, not
    !! taken from a zero-size array constructor, which gfortran copies into
    !! an unallocated component when the model is copied).
    pure subroutine limit_empty(slot)
        type(family_slot_t), intent(out) :: slot   !! the slot, holding the empty family
        type(joint_limit_t), allocatable :: jl(:)
        type(joint_range_t), allocatable :: jr(:)
        allocate (jl(0), jr(0)); allocate (slot%f, source=limit_family_t(items=jl, ranges=jr))
    end subroutine limit_empty

end module hn_limit_family
