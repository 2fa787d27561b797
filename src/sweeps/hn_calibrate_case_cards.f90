!> The calibration deck's cards of its cases (docs/sweeps.md): CASE, the
!! DATA of each case (volunteers, a reference CSV or published peaks), the
!! RATED cards of a reference case, and the STANDING, RETURN and REST cases
!! at rest; each a handler of the card engine (hn_card_engine) on the
!! calibration deck being read (calibration_reading_t), with its located
!! checks. The registry of the deck's cards is hn_calibrate_deck's.
module hn_calibrate_case_cards
    use hn_kinds, only: wp, one, msglen
    use hn_case, only: path_len
    use hn_card_engine, only: card_deck_t
    use hn_volunteer_data, only: is_peak_table
    use hn_calibrate_types, only: calibration_reading_t, standing_case_t
    implicit none
    private

    public :: read_case_card, read_data_card, read_rated_card, read_standing_card

contains

    !> The CASE card: a case deck (columns 11-70) and its weight (F7, default 1).
    subroutine read_case_card(deck, i)
        class(card_deck_t), intent(inout) :: deck     !! the calibration deck (calibration_reading_t)
        integer, intent(in) :: i                      !! the card's line
        real(wp) :: w
        select type (st => deck)
        type is (calibration_reading_t)
            st%cal%decks = [character(len=path_len) :: st%cal%decks, adjustl(st%rd%lines(i)%text(11:70))]
            call st%rd%real(i, 7, 'case weight', '-', w, 1.0e-6_wp, 1.0e6_wp, default=one)
            st%cal%weight = [st%cal%weight, w]
        end select
    end subroutine read_case_card

    !> The DATA card: the last case's volunteer directory or reference CSV (a name
    !! ending in .csv), found as an INCLUDE file is: next to the calibration
    !! deck, in the working directory, then on the include path (-I,
    !! HHNECK_PATH); one DATA card after each CASE card.
    subroutine read_data_card(deck, i)
        class(card_deck_t), intent(inout) :: deck     !! the calibration deck (calibration_reading_t)
        integer, intent(in) :: i                      !! the card's line
        character(len=:), allocatable :: dname, found
        character(len=msglen) :: msg
        select type (st => deck)
        type is (calibration_reading_t)
            if (size(st%cal%data) /= size(st%cal%decks) - 1) then
                call st%rd%fail(st%rd%where(i)//' (DATA card): expected one DATA card after each CASE card')
                return
            end if
            dname = trim(adjustl(st%rd%lines(i)%text(11:80)))
            st%is_ref = [st%is_ref, is_csv(dname)]
            call st%rd%find_file(dname, st%rd%lines(i)%source, found, msg, directory=.not. st%is_ref(size(st%is_ref)))
            if (len(found) == 0) then
                call st%rd%fail(st%rd%where(i)//' (DATA card): '//trim(msg))
                return
            end if
            st%cal%data = [character(len=path_len) :: st%cal%data, found]
            st%data_line = [st%data_line, i]
            ! a CSV whose header starts with `peak`: published peaks, not curves
            st%is_pub = [st%is_pub, st%is_ref(size(st%is_ref)) .and. is_peak_table(found)]
            if (st%is_pub(size(st%is_pub))) st%is_ref(size(st%is_ref)) = .false.
        end select
    end subroutine read_data_card

    !> The RATED card: a card of the last case, whose DATA card names a reference
    !! CSV; its fields are read with the CSV (rated_columns, hn_calibrate_cases).
    subroutine read_rated_card(deck, i)
        class(card_deck_t), intent(inout) :: deck     !! the calibration deck (calibration_reading_t)
        integer, intent(in) :: i                      !! the card's line
        select type (st => deck)
        type is (calibration_reading_t)
            if (size(st%cal%decks) == 0 .or. size(st%is_ref) /= size(st%cal%decks)) then
                call st%rd%fail(st%rd%where(i)//', columns 1-8 (RATED card): expected RATED cards after the DATA '// &
                                'card of a case (a reference CSV)')
                return
            end if
            if (.not. st%is_ref(size(st%is_ref))) then
                call st%rd%fail(st%rd%where(i)//', columns 1-8 (RATED card): the DATA card before it names a '// &
                                'directory of volunteer runs; expected RATED cards after the DATA card of a '// &
                                'reference CSV (a name ending in .csv)')
                return
            end if
            st%rated_line = [st%rated_line, i]
            st%rated_case = [st%rated_case, size(st%cal%decks)]
        end select
    end subroutine read_rated_card

    !> STANDING deck (columns 11-70) bound (F7, deg): a run of the deck, the
    !! model at rest, must keep every joint rotation within the bound of its
    !! start; with STANDING cards they judge standing in place of the
    !! volunteer cases' linear margin at rest. RETURN deck bound: a run of the
    !! deck (a push) must end with the head's rotation vector relative to R
    !! (HEADL_VX, _VY, _VZ) within the bound of its start. REST deck bound:
    !! the head's rotation vector within the bound of its start throughout.
    subroutine read_standing_card(deck, i)
        class(card_deck_t), intent(inout) :: deck     !! the calibration deck (calibration_reading_t)
        integer, intent(in) :: i                      !! the card's line
        type(standing_case_t) :: sc
        select type (st => deck)
        type is (calibration_reading_t)
            sc%deck = adjustl(st%rd%lines(i)%text(11:70))
            sc%kind = st%rd%key(i)
            if (len_trim(sc%deck) == 0) then
                call st%rd%fail(st%rd%where(i)//', columns 11-70 ('//trim(st%rd%key(i))//' card): found no deck; '// &
                                'expected the deck of the model at rest'//trim(merge(' or after a push', &
                                                                                      '                ', &
                                                                                      sc%kind /= 'STANDING')))
                return
            end if
            call st%rd%real(i, 7, 'largest excursion', 'deg', sc%bound, 1.0e-3_wp, 90.0_wp)
            if (st%rd%failed()) return
            st%cal%stand = [st%cal%stand, sc]
        end select
    end subroutine read_standing_card

    !> A DATA name ending in .csv (any case): a reference CSV.
    pure logical function is_csv(name)
        character(len=*), intent(in) :: name   !! the DATA card's name
        integer :: n
        n = len_trim(name)
        is_csv = .false.
        if (n > 4) is_csv = any(name(n - 3:n) == ['.csv', '.CSV', '.Csv'])
    end function is_csv

end module hn_calibrate_case_cards
