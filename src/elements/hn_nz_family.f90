!> The NZSPRINGS family: non-linear rotational joint springs with a neutral
!! zone (beyond the paper), one per joint rotation coordinate (NZSPRING cards).
!! They stand for the whole functional spinal unit's moment-rotation curve
!! measured in pure-moment segment tests (Panjabi et al. 2001, Nightingale
!! et al. 2007): soft near the neutral posture (the neutral zone), stiffening
!! exponentially towards the range of motion. With D = x - x_n the
!! coordinate's excursion from its neutral value (NEUTRAL cards), on either
!! side s of the neutral value (s = + for D >= 0, - for D < 0)
!!
!!   Q(D) = -sign(D) M0_s sinh(|D| / ths_s)
!!
!! (slope M0_s/ths_s at neutral, growing e-fold every ths_s), continued
!! linearly with its slope once |Q| reaches Mlin (so that a run far past
!! the data stays integrable), elastic energy
!!   U = M0_s ths_s (cosh(|D|/ths_s) - 1)   (+ the linear part's beyond Mlin).
!! Output per spring: its generalized force Q [N m].
module hn_nz_family
    use hn_kinds, only: wp, zero, one, half, deg
    use hn_deck_reader, only: deck_reader_t
    use hn_element_cards, only: card_context_t, active_coordinate, coord_names
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t
    use hn_tree, only: body_tree_t
    use hn_element_family, only: element_family_t, family_work_t, family_channel_t, element_table_t, max_family_items, item_len, &
                                 warning_len, add_warning
    use hn_family_registration, only: family_registration_t
    use hn_element_cards, only: family_card_t, unique_coordinate
    use hn_element_family, only: family_slot_t
    use hn_element_family, only: family_energy_t, tangent_work_t
    implicit none
    private

    public :: nz_spring_t, nz_family_t, nz_moment, nz_slope, nz_energy, nz_springs_of
    public :: nz_registration

    real(wp), parameter :: ref_nz_stiffness = 10.0_wp   !! N m/rad: the order of a neutral zone's slope (segment data)
    real(wp), parameter :: default_mlin = 100.0_wp      !! N m: where the law turns linear unless the card says
    real(wp), parameter :: far_nz = 100.0_wp            !! "two orders of magnitude" above ref_nz_stiffness

    !> One neutral-zone spring on a joint rotation.
    type :: nz_spring_t
        character(len=16) :: label = ''   !! joint and coordinate, for messages and channels (C5 RY)
        integer :: body = 0               !! body whose coordinate it acts on
        integer :: local = 0              !! local coordinate 4..6 (RX, RY, RZ)
        integer :: dof = 0                !! active coordinate number
        real(wp) :: xn = zero             !! neutral value of the coordinate [rad]
        real(wp) :: m0(2) = zero          !! M0 on the + and - side [N m]
        real(wp) :: ths(2) = one*deg      !! ths on the + and - side [rad]
        real(wp) :: mlin = default_mlin   !! |Q| beyond which the law is linear [N m]
    end type nz_spring_t

    !> The neutral-zone springs of a model.
    type, extends(element_family_t) :: nz_family_t
        type(nz_spring_t), allocatable :: items(:)
        integer :: nread = 0        !! springs read from the deck so far (room for every card until end_cards)
        integer :: ndropped = 0     !! cards dropped: on locked or merged coordinates
    contains
        procedure :: read_card => nz_read_card
        procedure :: end_cards => nz_end_cards
        procedure :: count => nz_count
        procedure :: ncomp => nz_ncomp
        procedure :: set_neutral => nz_neutral
        procedure :: add_loads => nz_loads
        procedure :: add_tangent => nz_tangent
        procedure :: switch_count => nz_switch_count
        procedure :: switching => nz_switching
        procedure :: channels => nz_channels
        procedure :: result_table => nz_table
        procedure :: plausibility => nz_plausibility
        procedure :: scale_items => nz_items
        procedure :: scale => nz_scale
        procedure :: stiffen => nz_stiffen
        procedure :: prestrain => nz_prestrain
    end type nz_family_t

contains

    !> Side of the excursion d: 1 (+, d >= 0) or 2 (-).
    elemental integer function side(d) result(s)
        real(wp), intent(in) :: d
        s = merge(1, 2, d >= zero)
    end function side

    !> The excursion |D| at which the law turns linear, ths asinh(Mlin/M0) [rad].
    elemental real(wp) function linear_from(m0, ths, mlin) result(dl)
        real(wp), intent(in) :: m0, ths, mlin
        if (m0 <= zero) then
            dl = huge(one)
        else
            dl = ths*asinh(mlin/m0)
        end if
    end function linear_from

    !> Where coordinate x lies on the spring's law: its side s (1 = +,
    !! 2 = -), the excursion |D| and the excursion dl where the law turns linear.
    elemental subroutine law_point(sp, x, s, a, dl)
        type(nz_spring_t), intent(in) :: sp
        real(wp), intent(in) :: x
        integer, intent(out) :: s
        real(wp), intent(out) :: a, dl
        s = side(x - sp%xn)
        a = abs(x - sp%xn)
        dl = linear_from(sp%m0(s), sp%ths(s), sp%mlin)
    end subroutine law_point

    !> Generalized force Q of the spring at coordinate x [N m] (module doc).
    elemental real(wp) function nz_moment(sp, x) result(q)
        type(nz_spring_t), intent(in) :: sp   !! the spring
        real(wp), intent(in) :: x             !! its coordinate [rad]
        real(wp) :: a, dl
        integer :: s
        call law_point(sp, x, s, a, dl)
        if (a <= dl) then
            q = sp%m0(s)*sinh(a/sp%ths(s))
        else
            q = sp%mlin + nz_slope(sp, x)*(a - dl)
        end if
        q = -sign(one, x - sp%xn)*q
    end function nz_moment

    !> Stiffness -dQ/dx of the spring at coordinate x [N m/rad].
    elemental real(wp) function nz_slope(sp, x) result(k)
        type(nz_spring_t), intent(in) :: sp   !! the spring
        real(wp), intent(in) :: x             !! its coordinate [rad]
        real(wp) :: a, dl
        integer :: s
        call law_point(sp, x, s, a, dl)
        k = sp%m0(s)*cosh(min(a, dl)/sp%ths(s))/sp%ths(s)
    end function nz_slope

    !> Elastic energy of the spring at coordinate x [J] (module doc).
    elemental real(wp) function nz_energy(sp, x) result(u)
        type(nz_spring_t), intent(in) :: sp   !! the spring
        real(wp), intent(in) :: x             !! its coordinate [rad]
        real(wp) :: a, dl, e
        integer :: s
        call law_point(sp, x, s, a, dl)
        u = sp%m0(s)*sp%ths(s)*(cosh(min(a, dl)/sp%ths(s)) - one)
        if (a > dl) then
            e = a - dl
            u = u + sp%mlin*e + half*nz_slope(sp, x)*e**2
        end if
    end function nz_energy

    !> Number of springs.
    pure integer function nz_count(this) result(n)
        class(nz_family_t), intent(in) :: this   !! the family
        n = 0
        if (allocated(this%items)) n = size(this%items)
    end function nz_count

    !> Output rows per spring: its generalized force.
    pure integer function nz_ncomp(this) result(n)
        class(nz_family_t), intent(in) :: this   !! the family
        n = 1
    end function nz_ncomp

    !> Nothing to set up: the neutral values come from the tree's NEUTRAL cards when read.
    pure subroutine nz_neutral(this, kin)
        class(nz_family_t), intent(inout) :: this   !! the family (unchanged)
        type(kinematics_t), intent(in) :: kin       !! kinematics of the neutral configuration (unused)
    end subroutine nz_neutral

    !> The pre-strain: every spring's neutral value x_n moved by its
    !! coordinate's displacement dx (the springs act on coordinates, so
    !! kin is not needed).
    pure subroutine nz_prestrain(this, kin, dx)
        class(nz_family_t), intent(inout) :: this   !! the family; out: x_n + dx
        type(kinematics_t), intent(in) :: kin       !! kinematics of the displaced neutral (unused)
        real(wp), intent(in) :: dx(:)               !! displacement of the active coordinates [m, rad]
        integer :: e
        do e = 1, size(this%items)
            this%items(e)%xn = this%items(e)%xn + dx(this%items(e)%dof)
        end do
    end subroutine nz_prestrain

    !> The springs' generalized forces on their coordinates; their stored energy.
    pure subroutine nz_loads(this, t, kin, x, xd, loads, out, work, energy)
        class(nz_family_t), intent(in) :: this        !! the family
        real(wp), intent(in) :: t                     !! time [s]
        type(kinematics_t), intent(in) :: kin         !! kinematics at (x, xd)
        real(wp), intent(in) :: x(:)                  !! active coordinates [m, rad]
        real(wp), intent(in) :: xd(:)                 !! their rates [m/s, rad/s]
        type(body_loads_t), intent(inout) :: loads    !! generalized forces, the family's added
        real(wp), intent(inout) :: out(:, :)          !! (1, n) the springs' Q [N m]
        type(family_work_t), intent(inout) :: work    !! scratch (unused)
        type(family_energy_t), intent(inout) :: energy !! energy stored, power dissipated and absorbed, the family's added
        integer :: e
        do e = 1, size(this%items)
            associate (sp => this%items(e))
                out(1, e) = nz_moment(sp, x(sp%dof))
                loads%q(sp%dof) = loads%q(sp%dof) + out(1, e)
                energy%u_elastic = energy%u_elastic + nz_energy(sp, x(sp%dof))
            end associate
        end do
    end subroutine nz_loads

    !> K_jj += -dQ/dx of each spring on its coordinate (the closed-form slope); no damping.
    pure subroutine nz_tangent(this, tree, kin, t, x, xd, kgen, cgen, tw)
        class(nz_family_t), intent(in) :: this        !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree (unused)
        type(kinematics_t), intent(in) :: kin         !! kinematics (unused)
        real(wp), intent(in) :: t                     !! time [s]
        real(wp), intent(in) :: x(:)                  !! active coordinates
        real(wp), intent(in) :: xd(:)                 !! their rates
        real(wp), intent(inout) :: kgen(:, :)         !! generalized stiffness, the family's added
        real(wp), intent(inout) :: cgen(:, :)         !! generalized damping (unchanged)
        type(tangent_work_t), intent(inout) :: tw     !! scratch sized for the coordinates
        integer :: e, j
        do e = 1, size(this%items)
            j = this%items(e)%dof
            kgen(j, j) = kgen(j, j) + nz_slope(this%items(e), x(j))
        end do
    end subroutine nz_tangent

    !> No switching functions: the law is smooth (its slope may change at the neutral value).
    pure integer function nz_switch_count(this) result(n)
        class(nz_family_t), intent(in) :: this   !! the family
        n = 0
    end function nz_switch_count

    !> No switching functions.
    pure subroutine nz_switching(this, t, kin, x, sw)
        class(nz_family_t), intent(in) :: this        !! the family
        real(wp), intent(in) :: t                     !! time [s]
        type(kinematics_t), intent(in) :: kin         !! kinematics at x (unused)
        real(wp), intent(in) :: x(:)                  !! active coordinates (unused)
        real(wp), intent(out) :: sw(:)                !! (0) none
        sw = zero
    end subroutine nz_switching

    !> One channel per spring: NZ_body_coordinate [N m].
    pure function nz_channels(this, tree) result(c)
        class(nz_family_t), intent(in) :: this        !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree (body names)
        type(family_channel_t), allocatable :: c(:)
        integer :: e
        allocate (c(size(this%items)))
        do e = 1, size(this%items)
            associate (sp => this%items(e))
                c(e) = family_channel_t('NZ_'//trim(tree%name(sp%body))//'_'//coord_names(sp%local), 'N m', &
                                        'NZ SPRINGS', e, 1)
            end associate
        end do
    end function nz_channels

    !> No table in the result file (the springs act on coordinates, not between points).
    pure function nz_table(this) result(tab)
        class(nz_family_t), intent(in) :: this        !! the family
        type(element_table_t) :: tab
        tab%group = ''
    end function nz_table

    !> Springs whose neutral-zone slope M0/ths is two orders of magnitude
    !! above a segment's (a units slip: M0 in N mm, ths in rad); a slope far
    !! below is the element's purpose (a neutral zone the other elements carry).
    pure subroutine nz_plausibility(this, tree, warnings)
        class(nz_family_t), intent(in) :: this        !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree (unused: the label names the joint)
        character(len=warning_len), allocatable, intent(inout) :: warnings(:)  !! warnings, the family's added
        character(len=warning_len) :: w
        integer :: e, s
        real(wp) :: slope
        character(len=1), parameter :: sname(2) = ['+', '-']
        do e = 1, size(this%items)
            do s = 1, 2
                slope = this%items(e)%m0(s)/this%items(e)%ths(s)
                if (slope <= far_nz*ref_nz_stiffness) cycle
                write (w, '(4a,es10.3,a,es9.2,a)') 'neutral-zone spring on ', trim(this%items(e)%label), ' ', &
                    sname(s)//' slope M0/ths = ', slope, ' N m/rad is two or more orders of magnitude above '// &
                    'a segment''s ', ref_nz_stiffness, ' (check units)'
                call add_warning(warnings, w)
            end do
        end do
    end subroutine nz_plausibility

    !> M0 (both sides'), THS (both sides'), MLIN.
    pure subroutine nz_items(this, items)
        class(nz_family_t), intent(in) :: this        !! the family
        character(len=item_len), intent(out) :: items(max_family_items)   !! the properties
        items = ''
        items(1:3) = [character(len=item_len) :: 'M0', 'THS', 'MLIN']
    end subroutine nz_items

    !> Scale M0, ths or Mlin of every spring.
    pure subroutine nz_scale(this, item, factor)
        class(nz_family_t), intent(inout) :: this   !! the family
        character(len=*), intent(in) :: item        !! M0, THS or MLIN
        real(wp), intent(in) :: factor              !! the factor
        integer :: e
        do e = 1, size(this%items)
            associate (sp => this%items(e))
                select case (item)
                case ('M0'); sp%m0 = factor*sp%m0
                case ('THS'); sp%ths = factor*sp%ths
                case ('MLIN'); sp%mlin = factor*sp%mlin
                end select
            end associate
        end do
    end subroutine nz_scale

    !> STIFFEN: M0 of every spring (the moment at every excursion scales).
    pure subroutine nz_stiffen(this, factor)
        class(nz_family_t), intent(inout) :: this   !! the family
        real(wp), intent(in) :: factor              !! the factor
        integer :: e
        do e = 1, size(this%items)
            this%items(e)%m0 = factor*this%items(e)%m0
        end do
    end subroutine nz_stiffen

    !> The springs of a model's family slot (a copy; none when the slot holds another family).
    pure function nz_springs_of(fam) result(items)
        class(element_family_t), intent(in) :: fam   !! the slot's family
        type(nz_spring_t), allocatable :: items(:)
        select type (fam)
        type is (nz_family_t)
            items = fam%items
        class default
            allocate (items(0))
        end select
    end function nz_springs_of

    !> An NZSPRING card: body, rotation coordinate, M0+ [N m], ths+ [deg],
    !! M0- [N m], ths- [deg], Mlin [N m] (default 100); dropped on a locked
    !! or merged coordinate.
    subroutine nz_read_card(this, rd, ctx, i, key)
        class(nz_family_t), intent(inout) :: this   !! the family; out: the card's spring added
        type(deck_reader_t), intent(inout) :: rd    !! the deck: card images, located field access, the first error
        type(card_context_t), intent(inout) :: ctx  !! the deck's bodies and the reduced tree
        integer, intent(in) :: i                    !! the card's first deck line
        character(len=*), intent(in) :: key         !! the card name (NZSPRING)
        type(nz_spring_t) :: sp
        integer :: kb, m, j
        logical :: merged
        ! room for every card, trimmed by end_cards (appending one by one is quadratic)
        if (ctx%needs_room(key, this%nread, size(this%items))) then
            deallocate (this%items)
            allocate (this%items(ctx%ncards(key)))
        end if
        call active_coordinate(rd, i, ctx%tree, ctx%bnames, ctx%bmap, kb, m, j, .true., merged)
        if (rd%failed()) return
        if (merged) then
            this%ndropped = this%ndropped + 1
            return
        end if
        if (m <= 3) then
            call rd%fail(rd%context(i, 2, 'coordinate')//': found '//coord_names(m)//'; expected a rotation '// &
                         '(RX, RY or RZ): NZSPRING cards hold joint rotations')
            return
        end if
        if (j == 0) then
            this%ndropped = this%ndropped + 1
            return
        end if
        sp = nz_spring_t()
        sp%body = kb; sp%local = m; sp%dof = j
        sp%label = trim(ctx%tree%name(kb))//' '//coord_names(m)
        sp%xn = ctx%tree%q_ref(m, kb)
        call rd%real(i, 3, 'M0 on the + side', 'N m', sp%m0(1), zero, 1.0e4_wp)
        call rd%real(i, 4, 'ths on the + side', 'deg', sp%ths(1), 0.01_wp, 90.0_wp)
        call rd%real(i, 5, 'M0 on the - side', 'N m', sp%m0(2), zero, 1.0e4_wp)
        call rd%real(i, 6, 'ths on the - side', 'deg', sp%ths(2), 0.01_wp, 90.0_wp)
        call rd%real(i, 7, 'moment where the law turns linear Mlin', 'N m', sp%mlin, 1.0e-3_wp, 1.0e5_wp, &
                     default=default_mlin)
        if (rd%failed()) return
        sp%ths = sp%ths*deg
        this%nread = this%nread + 1
        this%items(this%nread) = sp
    end subroutine nz_read_card

    !> The springs read: no room left over; a scene note of those dropped.
    subroutine nz_end_cards(this, rd, ctx)
        class(nz_family_t), intent(inout) :: this   !! the family; out: items trimmed
        type(deck_reader_t), intent(inout) :: rd    !! the deck (unused)
        type(card_context_t), intent(inout) :: ctx  !! out: the note of the springs dropped
        character(len=100) :: note
        this%items = this%items(1:this%nread)
        if (this%ndropped > 0) then
            write (note, '(i0,a)') this%ndropped, ' NEUTRAL-ZONE SPRINGS DROPPED: ON LOCKED OR MERGED COORDINATES'
            call ctx%add_note(note)
        end if
    end subroutine nz_end_cards

    !> The registry's entry of the neutral-zone springs: name NZSPRINGS, its card
    !! NZSPRING (one per body and coordinate), and the family with no elements.
    pure function nz_registration() result(r)
        type(family_registration_t) :: r
        r = family_registration_t('NZSPRINGS', [ &
            family_card_t('NZSPRING', 0, 0, unique=unique_coordinate, coordinate=.true.)], nz_empty)
    end function nz_registration

    !> A family of nzsprings with no elements (its arrays allocated with size 0, not
    !! taken from a zero-size array constructor, which gfortran copies into
    !! an unallocated component when the model is copied).
    pure subroutine nz_empty(slot)
        type(family_slot_t), intent(out) :: slot   !! the slot, holding the empty family
        type(nz_spring_t), allocatable :: nz(:)
        allocate (nz(0)); allocate (slot%f, source=nz_family_t(items=nz))
    end subroutine nz_empty

end module hn_nz_family
