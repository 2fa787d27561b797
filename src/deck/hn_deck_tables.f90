!> The table cards of a deck: TABLE with its data continuation cards or
!! its CSV file, and PULSE, a table of a named shape (`table_cards`).
module hn_deck_tables
    use hn_kinds, only: wp, zero, one, msglen, g_std
    use hn_case, only: case_t
    use hn_deck_reader, only: deck_reader_t, int_str, upper
    use hn_tables, only: table_set
    use hn_csv, only: read_two_columns
    use hn_pulses, only: pulse_shapes, pulse_code, pulse_dv_factor, pulse_knots, pulse_triangle, pulse_trapezoid, &
                         pulse_halfsine
    use hn_deck_state, only: max_table_points, tiny_value, card_t, named_table_t, add_scene_note, real_str
    implicit none
    private

    public :: table_cards, pulse_card

contains

    !> TABLE cards with their data continuation cards, and PULSE cards
    !! (tables of the same namespace, in deck order).
    subroutine table_cards(rd, cards, tabs, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(card_t), intent(in) :: cards(:)  !! the deck's cards with their continuation cards (group_cards)
        type(named_table_t), allocatable, intent(out) :: tabs(:)  !! the deck's named tables (TABLE, PULSE)
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        integer :: k, nt, i, npts, c, stat, bad
        character(len=12) :: v1, v2
        real(wp) :: tscale, yscale
        real(wp), allocatable :: t(:), y(:)
        nt = count(cards%key == 'TABLE' .or. cards%key == 'PULSE')
        allocate (tabs(nt))
        nt = 0
        do k = 1, size(cards)
            if (cards(k)%key == 'PULSE') then
                nt = nt + 1
                call pulse_card(rd, cards(k)%first, tabs(nt), cs)
                if (rd%failed()) return
                cycle
            end if
            if (cards(k)%key /= 'TABLE') cycle
            nt = nt + 1
            i = cards(k)%first
            tabs(nt)%line = i
            call rd%name(i, 1, 'table name', tabs(nt)%name)
            if (rd%failed()) return
            call rd%int(i, 2, 'number of points', npts, 1, max_table_points)
            call rd%real(i, 3, 'time scale', 's per unit', tscale, 1.0e-9_wp, 1.0e3_wp, default=one)
            call rd%real(i, 4, 'value scale', 'per unit', yscale, -1.0e9_wp, 1.0e9_wp, default=one)
            if (rd%failed()) return
            if (upper(adjustl(rd%raw(i, 5))) == 'CSV') then
                call csv_points(rd, i, tabs(nt)%name, npts, t, y)
            else
                call card_points(rd, i, cards(k)%ncont, tabs(nt)%name, npts, t, y)
            end if
            if (rd%failed()) return
            if (maxval(abs(y)) > zero .and. maxval(abs(y))*abs(yscale) < tiny_value) then
                write (v1, '(es11.2e3)') yscale
                write (v2, '(es11.2e3)') maxval(abs(y))*abs(yscale)
                tabs(nt)%warning = 'table '//trim(tabs(nt)%name)//': value scale '//trim(adjustl(v1))// &
                                   ' makes its largest value '//trim(adjustl(v2))//', zero in effect; check F4 at '// &
                                   rd%where(i)
            end if
            call table_set(tabs(nt)%tab, t*tscale, y*yscale, stat, bad)
            if (bad > 0) then
                c = i + 1 + (bad - 1)/3
                call rd%fail(rd%where(c)//' (TABLE '//trim(tabs(nt)%name)//' data, point '// &
                             trim(int_str(bad))//'): times must increase strictly; found '// &
                             trim(real_str(t(bad)))//' after '//trim(real_str(t(bad - 1))))
                return
            end if
            deallocate (t, y)
        end do
    end subroutine table_cards

    !> PULSE name shape peak dv duration onset f: a table of a named
    !! shape (hn_pulses), given its peak or its velocity change.
    subroutine pulse_card(rd, i, tab, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i                   !! the PULSE card image
        type(named_table_t), intent(inout) :: tab  !! the table (name, knots, line)
        type(case_t), intent(inout) :: cs          !! the case (the listing's note of the pulse)
        character(len=10) :: s
        character(len=:), allocatable :: note, shape_text
        character(len=12) :: v
        real(wp) :: peak, dv, duration, onset, frac, factor
        real(wp), allocatable :: t(:), a(:)
        integer :: code, stat
        tab%line = i
        call rd%name(i, 1, 'table name', tab%name)
        call rd%choice(i, 2, 'shape', pulse_shapes, s)
        if (rd%failed()) return
        code = pulse_code(s)
        ! a number shifted across the F3/F4 boundary is named as such, not as "both"
        call rd%separated(i, 3, 'peak')
        call rd%separated(i, 4, 'velocity change')
        if (rd%failed()) return
        if (rd%is_blank(i, 3) .eqv. rd%is_blank(i, 4)) then
            call rd%fail(rd%where(i)//', columns 31-50 (PULSE card, peak and velocity change): found '// &
                         trim(merge('both   ', 'neither', .not. rd%is_blank(i, 3)))//'; expected either the peak (F3) '// &
                         'or the velocity change (F4), the other blank'//shifted())
            return
        end if
        call rd%real(i, 5, 'duration', 's', duration, 1.0e-6_wp, 1.0e3_wp)
        call rd%real(i, 6, 'onset', 's', onset, zero, 1.0e3_wp, default=zero)
        frac = 0.5_wp
        select case (code)
        case (pulse_triangle)
            call rd%real(i, 7, 'time of the peak', 'fraction of the duration', frac, 0.001_wp, 0.999_wp, &
                         default=0.5_wp)
        case (pulse_trapezoid)
            call rd%real(i, 7, 'rise time', 'fraction of the duration', frac, 0.001_wp, 0.499_wp, default=0.25_wp)
        case default
            if (.not. rd%is_blank(i, 7)) then
                call rd%fail(rd%context(i, 7, 'fraction')//': found "'//trim(rd%raw(i, 7))//'"; expected blank '// &
                             '(F7 is the time of the peak of a TRIANGLE or the rise time of a TRAPEZOID)')
                return
            end if
        end select
        if (rd%failed()) return
        factor = pulse_dv_factor(code, duration, frac)
        if (.not. rd%is_blank(i, 3)) then
            call rd%real(i, 3, 'peak', 'table unit', peak, -1.0e9_wp, 1.0e9_wp)
            if (rd%failed()) return
            if (peak == zero) call rd%fail(rd%context(i, 3, 'peak')//': found 0; expected a non-zero peak')
            dv = peak*factor
        else
            call rd%real(i, 4, 'velocity change', 'table unit x s', dv, -1.0e9_wp, 1.0e9_wp)
            if (rd%failed()) return
            if (dv == zero) call rd%fail(rd%context(i, 4, 'velocity change')// &
                                         ': found 0; expected a non-zero velocity change')
            peak = dv/factor
        end if
        if (rd%failed()) return
        call pulse_knots(code, peak, duration, onset, frac, t, a)
        call table_set(tab%tab, t, a, stat)
        if (stat /= 0) then
            call rd%fail(rd%where(i)//' (PULSE '//trim(tab%name)//'): the pulse makes no table')
            return
        end if
        select case (code)
        case (pulse_halfsine); shape_text = 'HALF-SINE'
        case (pulse_triangle); write (v, '(f0.2)') frac; shape_text = 'TRIANGLE (PEAK AT '//trim(zero_lead(v))//' T)'
        case (pulse_trapezoid); write (v, '(f0.2)') frac; shape_text = 'TRAPEZOID (RISE '//trim(zero_lead(v))//' T)'
        case default; shape_text = trim(pulse_shapes(code))
        end select
        write (v, '(f0.2)') peak/g_std
        note = 'PULSE '//trim(tab%name)//': '//shape_text//', PEAK '//three_digits(peak)//' ('// &
               '9.80665 M/S2 = 1 G: '//trim(zero_lead(v))//' G), DV '//three_digits(dv)//', '// &
               ms(duration)//' MS FROM '//ms(onset)//' MS'
        if (len(note) > 100) note = 'PULSE '//trim(tab%name)//': '//shape_text//', PEAK '//three_digits(peak)// &
                                    ' ('//trim(zero_lead(v))//' G), DV '//three_digits(dv)//', '// &
                                    ms(duration)//' MS FROM '//ms(onset)//' MS'
        call add_scene_note(cs, note)
    contains
        !> The likely cause of "both": the duration (F5 blank) written in F4,
        !! or F4's text shifted from the start of its field.
        function shifted() result(r)
            character(len=:), allocatable :: r
            integer :: p
            r = ''
            if (rd%is_blank(i, 3)) return
            p = verify(rd%lines(i)%text(41:50), ' ')
            if (rd%is_blank(i, 5)) then
                r = ' (F5, the duration, is blank: is it written in F4, columns 41-50?)'
            else if (p > 1 .and. len_trim(rd%lines(i)%text(41:50)) < 10) then   ! neither left nor right aligned
                r = ' (the text of F4 begins at column '//trim(int_str(40 + p))//', not 41: are the fields '// &
                    'after F3 shifted by '//trim(int_str(p - 1))//' columns?)'
            end if
        end function shifted
        !> x with three significant digits (E format outside 0.01 .. 1E5).
        function three_digits(x) result(r)
            real(wp), intent(in) :: x
            character(len=:), allocatable :: r
            character(len=16) :: b
            integer :: e
            if (abs(x) >= 0.01_wp .and. abs(x) < 1.0e5_wp) then
                e = floor(log10(abs(x)))
                write (b, '(f0.'//achar(48 + max(0, 2 - e))//')') x
                b = zero_lead(b)
                if (max(0, 2 - e) == 0) b = trim(b)//'.0'
            else
                write (b, '(es10.2)') x
            end if
            r = trim(adjustl(b))
        end function three_digits
        !> A time [s] in ms with one decimal.
        function ms(x) result(r)
            real(wp), intent(in) :: x
            character(len=:), allocatable :: r
            character(len=16) :: b
            write (b, '(f0.1)') 1000*x
            r = trim(zero_lead(b))
        end function ms
    end subroutine pulse_card

    !> A number written with f0.d, with its leading zero (".5" -> "0.5").
    pure function zero_lead(b) result(r)
        character(len=*), intent(in) :: b
        character(len=len(b) + 1) :: r
        character(len=len(b)) :: c
        c = adjustl(b)
        if (c(1:1) == '.') then
            r = '0'//c
        else if (c(1:2) == '-.') then
            r = '-0'//c(2:)
        else
            r = c
        end if
    end function zero_lead

    !> The npts (time, value) points of a TABLE on its continuation cards:
    !! three pairs per card, fields after the last point blank.
    subroutine card_points(rd, i, ncont, name, npts, t, y)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i, ncont, npts       !! TABLE card image, its continuation cards, points
        character(len=*), intent(in) :: name        !! table name (messages)
        real(wp), allocatable, intent(out) :: t(:), y(:)
        integer :: j, c, f
        allocate (t(npts), y(npts))
        do j = 1, npts
            c = i + 1 + (j - 1)/3
            f = 2*mod(j - 1, 3) + 1
            call rd%real(c, f, 'time', 'table time unit', t(j), -1.0e7_wp, 1.0e7_wp)
            call rd%real(c, f + 1, 'value', 'table unit', y(j), -1.0e12_wp, 1.0e12_wp)
        end do
        if (rd%failed()) return
        c = i + ncont
        do f = 2*mod(npts - 1, 3) + 3, 7
            if (.not. rd%is_blank(c, f)) then
                call rd%fail(rd%where(c)//' (TABLE '//trim(name)//' data): found "'// &
                             trim(rd%raw(c, f))//'" in field F'//achar(48 + f)//' after the last of '// &
                             trim(int_str(npts))//' points; expected blank (or a larger point count)')
                return
            end if
        end do
    end subroutine card_points

    !> The npts points of a TABLE from the two-column file named on its
    !! continuation card (columns 11-80; looked for as INCLUDE files are).
    subroutine csv_points(rd, i, name, npts, t, y)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i, npts              !! TABLE card image, declared points
        character(len=*), intent(in) :: name        !! table name (messages)
        real(wp), allocatable, intent(out) :: t(:), y(:)
        character(len=:), allocatable :: fname, path, bytes, why
        integer :: stat
        character(len=msglen) :: msg
        fname = trim(adjustl(rd%lines(i + 1)%text(11:80)))
        if (len(fname) == 0) then
            call rd%fail(rd%where(i + 1)//', columns 11-80 (TABLE '//trim(name)//' file): found no file name; '// &
                         'expected the path of a two-column (time, value) file')
            return
        end if
        call rd%read_data_file(i + 1, fname, path, bytes, stat, msg)
        if (stat /= 0) then
            call rd%fail(rd%where(i + 1)//' (TABLE '//trim(name)//' file): '//trim(msg))
            return
        end if
        call read_two_columns(bytes, t, y, stat, why)
        if (stat /= 0) then
            call rd%fail('TABLE '//trim(name)//' ('//rd%where(i)//'), file "'//path//'" '//why)
            return
        end if
        if (size(t) /= npts) then
            call rd%fail(rd%context(i, 2, 'number of points')//': TABLE '//trim(name)//' declares '// &
                         trim(int_str(npts))//' points; its file "'//path//'" has '//trim(int_str(size(t)))// &
                         ' data rows; expected the same number')
            return
        end if
    end subroutine csv_points

end module hn_deck_tables
