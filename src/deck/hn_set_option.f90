!> The command line's `--set KEY=VALUE` (and `--set KEY*=FACTOR`) as the
!! CHANGE card image it stands for (hn_changes reads it as it reads a
!! `--change` card):
!!
!!   BODY.body.MASS=4.2         CHANGE  SETk  BODY    body    MASS     SET    4.2
!!   BODY.body.INERTIA*=1.1     CHANGE  SETk  BODY    body    INERTIA  SCALE  1.1
!!   FAMILY.family.item*=1.2    CHANGE  SETk  FAMILY  family  item     SCALE  1.2
!!   CARD.Fn=VALUE              CHANGE  SETk  FIELDn  CARD    (blank)  SET    VALUE
!!   CARD.name.Fn*=FACTOR       CHANGE  SETk  FIELDn  CARD    name     SCALE  FACTOR
!!   CARD.name.key2.Fn=VALUE    CHANGE  SETk  FIELDn  CARD    name     SET    VALUE   key2
!!
!! Names are case-insensitive and at most ten characters; the value is a
!! real number of at most ten characters. A bad key or value is refused
!! with the option's number and the characters of the part at fault.
module hn_set_option
    use hn_kinds, only: wp, msglen
    use hn_deck_reader, only: parse_real, upper, int_str
    implicit none
    private

    public :: set_card

contains

    !> The CHANGE card image of the k-th `--set` option `text`; stat /= 0
    !! and `errmsg` ("--set k, characters a-b of "...": found ...; expected
    !! ...") when the key or the value is not of the forms above.
    subroutine set_card(text, k, card, stat, errmsg)
        character(len=*), intent(in) :: text          !! the option's argument, KEY=VALUE or KEY*=FACTOR
        integer, intent(in) :: k                      !! which --set option (1, 2, ...): the change's name SETk
        character(len=80), intent(out) :: card        !! the CHANGE card image
        integer, intent(out) :: stat                  !! 0, or 1 when the option is refused
        character(len=msglen), intent(out) :: errmsg  !! why ('' when stat = 0)
        character(len=:), allocatable :: key, value
        character(len=10) :: part(4), how, fk
        integer :: first(5), np, eq, p, n, a
        real(wp) :: v
        logical :: ok
        card = ''
        stat = 0
        errmsg = ''
        eq = index(text, '=')
        if (eq <= 1) then
            call refuse(1, len_trim(text), 'found no KEY=VALUE; expected e.g. BODY.HEAD.MASS=4.2, '// &
                        'FAMILY.DISCS.E*=1.2 or CONTROL.F5=1E-7')
            return
        end if
        how = 'SET'
        key = text(1:eq - 1)
        if (text(eq - 1:eq - 1) == '*') then
            how = 'SCALE'
            key = text(1:eq - 2)
        end if
        value = trim(text(eq + 1:))
        ! the key's parts, separated by points
        np = 0
        a = 1
        do p = 1, len(key) + 1
            if (p <= len(key)) then
                if (key(p:p) /= '.') cycle
            end if
            np = np + 1
            if (np > 4) then
                call refuse(1, len(key), 'found more than four parts in "'//key//'"; expected at most '// &
                            'CARD.name.key2.Fn')
                return
            end if
            first(np) = a
            if (p == a .or. p - a > 10) then
                call refuse(a, max(a, p - 1), 'found "'//key(a:p - 1)//'"; expected a name of 1 to 10 characters '// &
                            'between the points of the key')
                return
            end if
            part(np) = upper(key(a:p - 1))
            do n = a, p - 1
                if (index('ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-', key(n:n)) == 0) then
                    call refuse(n, n, 'found "'//key(n:n)//'"; expected letters, digits, _ or - in a name')
                    return
                end if
            end do
            a = p + 1
        end do
        first(np + 1) = len(key) + 2
        ! the value: a real number in ten columns
        if (len(value) == 0 .or. len(value) > 10) then
            call refuse(eq + 1, max(eq + 1, len_trim(text)), 'found "'//value//'"; expected a real number of at '// &
                        'most ten characters (a field of the CHANGE card)')
            return
        end if
        call parse_real(value, v, ok)
        if (.not. ok) then
            call refuse(eq + 1, len_trim(text), 'found "'//value//'"; expected a real number such as 4.2, -2 '// &
                        'or 1.5E-4')
            return
        end if
        if (np >= 2 .and. part(1) == 'BODY' .and. (part(np) == 'MASS' .or. part(np) == 'INERTIA')) then
            if (np /= 3) then
                call refuse(1, len(key), 'found "'//key//'"; expected BODY.body.'//trim(part(np)))
                return
            end if
            if (part(3) == 'INERTIA' .and. how == 'SET') then
                call refuse(eq, eq, 'found "="; a body''s inertia is scaled: expected BODY.'//trim(part(2))// &
                            '.INERTIA*=FACTOR')
                return
            end if
            card = image(['BODY      ', part(2), part(3)], '')
        else if (part(1) == 'FAMILY') then
            if (np /= 3) then
                call refuse(1, len(key), 'found "'//key//'"; expected FAMILY.family.item*=FACTOR')
                return
            end if
            if (how == 'SET') then
                call refuse(eq, eq, 'found "="; a family''s property is scaled: expected FAMILY.'// &
                            trim(part(2))//'.'//trim(part(3))//'*=FACTOR')
                return
            end if
            card = image(['FAMILY    ', part(2), part(3)], '')
        else
            n = field_number(part(np))
            if (np < 2 .or. n == 0) then
                call refuse(first(np), first(np + 1) - 2, 'found "'//key(first(np):first(np + 1) - 2)// &
                            '"; expected Fn, the field n = 1 to 21 of the card (F8 is F1 of its first '// &
                            'continuation card), BODY.body.MASS|INERTIA or FAMILY.family.item')
                return
            end if
            fk = 'FIELD'//trim(int_str(n))
            select case (np)
            case (2); card = image([fk, part(1), '          '], '')
            case (3); card = image([fk, part(1), part(2)], '')
            case default; card = image([fk, part(1), part(2)], part(3))
            end select
        end if
    contains
        !> The card image: CHANGE SETk KIND TARGET ITEM HOW VALUE [KEY2].
        function image(f, key2) result(c)
            character(len=10), intent(in) :: f(3)
            character(len=*), intent(in) :: key2
            character(len=80) :: c
            character(len=10) :: name
            name = 'SET'//trim(int_str(k))
            c = 'CHANGE    '//name//f(1)//f(2)//f(3)//how//value
            if (len(key2) > 0) c(71:80) = key2
        end function image
        !> n of "Fn" (1 to 21); 0 otherwise.
        pure integer function field_number(s) result(nf)
            character(len=*), intent(in) :: s
            integer :: ios
            nf = 0
            if (len_trim(s) < 2 .or. s(1:1) /= 'F' .or. verify(trim(s(2:)), '0123456789') /= 0) return
            read (s(2:), *, iostat=ios) nf
            if (ios /= 0 .or. nf < 1 .or. nf > 21) nf = 0
        end function field_number
        subroutine refuse(c1, c2, problem)
            integer, intent(in) :: c1, c2
            character(len=*), intent(in) :: problem
            stat = 1
            errmsg = '--set '//trim(int_str(k))//', characters '//trim(int_str(c1))//'-'//trim(int_str(c2))// &
                     ' of "'//trim(text)//'": '//problem
        end subroutine refuse
    end subroutine set_card

end module hn_set_option
