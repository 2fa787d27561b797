!> The coordinate cards of a deck: LOCK and NEUTRAL (read with the body
!! cards, before the tree is built), INITIAL and PRESCRIB
!! (`coordinate_cards`, once the tree and the tables are there).
module hn_deck_coordinates
    use hn_kinds, only: wp, zero, one, deg
    use hn_case, only: case_t
    use hn_deck_reader, only: deck_reader_t
    use hn_model, only: neutral_coordinates
    use hn_motion, only: motion_constant, motion_accel_table, motion_position_table, motion_harmonic, &
                         motion_rate_table
    use hn_deck_state, only: deck_state_t, add_scene_note, k_old, locked_error, active_coordinate, body_ref, coord_ref, &
                             table_ref, unit_of, unit_factor, unit_limit
    implicit none
    private

    public :: lock_card, neutral_card, coordinate_cards

contains

    !> LOCK body|ALL coordinate ...: lock coordinates at their neutral value.
    subroutine lock_card(rd, i, bnames, cs, locked_by)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        character(len=10), intent(in) :: bnames(:)  !! the names of the deck's bodies, in deck order
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        integer, intent(inout) :: locked_by(:, :)    !! (coordinate, body): the card that locked it first
        character(len=10) :: s
        integer :: kb, f, m, nset
        call rd%name(i, 1, 'body', s)
        if (rd%failed()) return
        kb = 0
        if (s /= 'ALL') kb = body_ref(rd, i, 1, 'body', bnames, .false.)
        nset = 0
        do f = 2, 7
            if (rd%is_blank(i, f)) cycle
            m = coord_ref(rd, i, f)
            if (rd%failed()) return
            if (kb == 0) then
                cs%model%tree%active(m, :) = .false.
                where (locked_by(m, :) == 0) locked_by(m, :) = i
            else
                cs%model%tree%active(m, kb) = .false.
                if (locked_by(m, kb) == 0) locked_by(m, kb) = i
            end if
            nset = nset + 1
        end do
        if (nset == 0) call rd%fail(rd%where(i)//', columns 21-80 (LOCK card): found no coordinate; '// &
                                    'expected one to six of TX TY TZ RX RY RZ')
    end subroutine lock_card

    !> NEUTRAL body coordinate value: the reference value of a coordinate.
    subroutine neutral_card(rd, i, bnames, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        character(len=10), intent(in) :: bnames(:)  !! the names of the deck's bodies, in deck order
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        integer :: kb, m
        real(wp) :: v
        kb = body_ref(rd, i, 1, 'body', bnames, .false.)
        m = coord_ref(rd, i, 2)
        if (rd%failed()) return
        call rd%real(i, 3, 'neutral value', unit_of(m), v, -unit_limit(m), unit_limit(m))
        cs%model%tree%q_ref(m, kb) = v*unit_factor(m)
    end subroutine neutral_card

    !> INITIAL and PRESCRIB cards. A card for a coordinate the scene locked
    !! is dropped when it only restates the neutral value; otherwise it is an
    !! error.
    subroutine coordinate_cards(rd, st, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(deck_state_t), intent(in) :: st  !! the deck's cards, bodies (names, where each went) and tables
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        integer :: k, i, kb, m, j, it, stat, ndrop
        real(wp) :: v, vd, fac, amp, freq, phase
        character(len=10) :: s
        character(len=100) :: note

        allocate (cs%x0(cs%model%tree%ndof), cs%xd0(cs%model%tree%ndof))
        cs%x0 = neutral_coordinates(cs%model)
        cs%xd0 = zero
        ndrop = 0
        do k = 1, size(st%cards)
            i = st%cards(k)%first
            select case (st%cards(k)%key)
            case ('INITIAL')
                call active_coordinate(rd, i, cs%model%tree, st%bnames, st%bmap, kb, m, j, .true.)
                if (rd%failed()) return
                if (j == 0) then
                    call rd%real(i, 3, 'initial value', unit_of(m), v, -unit_limit(m), unit_limit(m), &
                                 default=cs%model%tree%q_ref(m, kb)/unit_factor(m))
                    call rd%real(i, 4, 'initial rate', unit_of(m)//'/s', vd, -1.0e5_wp, 1.0e5_wp, default=zero)
                    if (abs(v*unit_factor(m) - cs%model%tree%q_ref(m, kb)) > 1.0e-12_wp .or. vd /= zero) then
                        call locked_error(rd, i, st%bnames, st%bmap, k_old(rd, i, st%bnames), m)
                        return
                    end if
                    ndrop = ndrop + 1
                    cycle
                end if
                fac = unit_factor(m)
                call rd%real(i, 3, 'initial value', unit_of(m), v, -unit_limit(m), unit_limit(m), &
                             default=cs%model%tree%q_ref(m, kb)/fac)
                call rd%real(i, 4, 'initial rate', unit_of(m)//'/s', vd, -1.0e5_wp, 1.0e5_wp, default=zero)
                cs%x0(j) = v*fac
                cs%xd0(j) = vd*fac
            case ('PRESCRIB')
                call active_coordinate(rd, i, cs%model%tree, st%bnames, st%bmap, kb, m, j, .true.)
                if (rd%failed()) return
                if (j == 0) then
                    call rd%name(i, 3, 'kind', s)
                    v = cs%model%tree%q_ref(m, kb)/unit_factor(m)
                    if (s == 'CONSTANT') call rd%real(i, 4, 'value', unit_of(m), v, -unit_limit(m), unit_limit(m), &
                                                      default=v)
                    if (rd%failed()) return
                    if (s /= 'CONSTANT' .or. abs(v*unit_factor(m) - cs%model%tree%q_ref(m, kb)) > 1.0e-12_wp) then
                        call locked_error(rd, i, st%bnames, st%bmap, k_old(rd, i, st%bnames), m)
                        return
                    end if
                    ndrop = ndrop + 1
                    cycle
                end if
                fac = unit_factor(m)
                call rd%name(i, 3, 'kind', s)
                if (rd%failed()) return
                select case (s)
                case ('CONSTANT')
                    call rd%real(i, 4, 'value', unit_of(m), v, -unit_limit(m), unit_limit(m), &
                                 default=cs%model%tree%q_ref(m, kb)/fac)
                    cs%model%motion(j) = motion_constant(v*fac)
                case ('ACCEL', 'POSITION', 'RATE')
                    it = table_ref(rd, i, 4, st%tabs)
                    if (rd%failed()) return
                    if (s == 'RATE') then
                        call rd%real(i, 5, 'initial value', unit_of(m), v, -unit_limit(m), unit_limit(m), &
                                     default=cs%model%tree%q_ref(m, kb)/fac)
                        call motion_rate_table(cs%model%motion(j), st%tabs(it)%tab%t, st%tabs(it)%tab%y*fac, &
                                               v*fac, stat)
                    else if (s == 'ACCEL') then
                        call rd%real(i, 5, 'initial value', unit_of(m), v, -unit_limit(m), unit_limit(m), &
                                     default=cs%model%tree%q_ref(m, kb)/fac)
                        call rd%real(i, 6, 'initial rate', unit_of(m)//'/s', vd, -1.0e5_wp, 1.0e5_wp, default=zero)
                        call motion_accel_table(cs%model%motion(j), st%tabs(it)%tab%t, st%tabs(it)%tab%y*fac, &
                                                v*fac, vd*fac, stat)
                    else
                        call motion_position_table(cs%model%motion(j), st%tabs(it)%tab%t, st%tabs(it)%tab%y*fac, stat)
                    end if
                case ('HARMONIC')
                    call rd%real(i, 4, 'amplitude', unit_of(m), amp, -unit_limit(m), unit_limit(m))
                    call rd%real(i, 5, 'frequency', 'Hz', freq, zero, 1.0e5_wp)
                    call rd%real(i, 6, 'phase', 'deg', phase, -3600.0_wp, 3600.0_wp, default=zero)
                    cs%model%motion(j) = motion_harmonic(cs%model%tree%q_ref(m, kb), amp*fac, &
                                                         2*acos(-one)*freq, phase*deg)
                case default
                    call rd%fail(rd%context(i, 3, 'kind')//': found "'// &
                                 trim(s)//'"; expected CONSTANT, ACCEL, RATE, POSITION or HARMONIC')
                    return
                end select
                if (rd%failed()) return
                cs%model%prescribed(j) = .true.
            end select
        end do
        if (ndrop > 0) then
            write (note, '(i0,a)') ndrop, ' INITIAL/PRESCRIB CARDS DROPPED: THEY HOLD LOCKED COORDINATES AT NEUTRAL'
            call add_scene_note(cs, note)
        end if
    end subroutine coordinate_cards

end module hn_deck_coordinates
