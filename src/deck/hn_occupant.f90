!> The OCCUPANT card: the model read from the deck (a 50th-percentile
!! male) scaled to another occupant size by dimensional analysis (Mertz
!! 1984, SAE 840884): three scale factors, on lengths (lambda_L), masses
!! (lambda_m) and the elastic modulus (lambda_E), give every other one:
!!
!!   density  lambda_rho = lambda_m / lambda_L^3
!!   time     lambda_t   = lambda_L sqrt(lambda_rho / lambda_E)
!!   force    lambda_F   = lambda_E lambda_L^2,   moment lambda_E lambda_L^3
!!
!! Body masses scale by lambda_m, inertias by lambda_m lambda_L^2, joint
!! points, neutral translations and the points of the elements on bodies
!! by lambda_L (the body map's `length`, applied as the element cards are
!! read); the element families' properties each by the law of their units
!! (`laws`, through the families' `scale` binding, as CHANGE ... FAMILY).
!!
!!   OCCUPANT  F1 size   H05F, H50M, H95M or SCALED
!!             F2 lambda_L, F3 lambda_m, F4 lambda_E (blank: the size's;
!!             SCALED needs F2, F3 blank: lambda_L^3, F4 blank: 1)
!!
!! The size's Nij intercepts become the criteria's occupant where
!! hn_injury has a sourced set for it (a CRITERIA card still chooses).
module hn_occupant
    use hn_kinds, only: wp, one, msglen
    use hn_deck_reader, only: deck_reader_t, field_text
    use hn_element_cards, only: card_t, body_map_t
    use hn_case, only: case_t
    use hn_model, only: model_t, scale_family, family_items
    use hn_families, only: family_index
    use hn_injury, only: occupant_index
    use hn_tree, only: tree_build
    implicit none
    private

    public :: occupant_size_t, sizes, size_index, scale_law_t, laws, occupant_scales_t, occupant_scales, law_factor
    public :: scale_tree, scale_families, occupant_bodies, occupant_elements

    !> A named occupant size: its scale factors relative to the 50th male.
    type :: occupant_size_t
        character(len=6) :: code = ''
        character(len=40) :: description = ''
        real(wp) :: lambda_l = one      !! lengths (stature ratio)
        real(wp) :: lambda_m = one      !! masses (body mass ratio)
        real(wp) :: lambda_e = one      !! elastic modulus (assumed equal)
    end type occupant_size_t

    !> The sizes. lambda_L: the ratio of statures, lambda_m: of body masses,
    !! of the Hybrid III dummies of that size to the 50th male's (stature
    !! 69.0 in, 172.3 lb; the 5th female 59.1 in, 108.0 lb: NHTSA, Hybrid III
    !! 5th Percentile Female, "Comparison of Weight, Sitting Height, and
    !! Stature for HYBRID III Family"; the 95th male 74 in (188 cm), 223 lb:
    !! the Hybrid III family as described by Humanetics and NHTSA).
    !! lambda_E = 1: tissue moduli equal across sizes (Mertz 1984).
    type(occupant_size_t), parameter :: sizes(*) = [ &
        occupant_size_t('H50M', '50TH PERCENTILE MALE (THE MODEL AS READ)', one, one, one), &
        occupant_size_t('H05F', '5TH PERCENTILE FEMALE', 59.1_wp/69.0_wp, 108.0_wp/172.3_wp, one), &
        occupant_size_t('H95M', '95TH PERCENTILE MALE', 74.0_wp/69.0_wp, 223.0_wp/172.3_wp, one)]

    !> One family property and the law it scales by: the factor is
    !! lambda_E^pe lambda_L^pl lambda_t^pt.
    type :: scale_law_t
        character(len=10) :: family = ''
        character(len=10) :: item = ''
        integer :: pe = 0, pl = 0, pt = 0
        character(len=24) :: units = ''   !! what the property is (the law's reason)
    end type scale_law_t

    !> The laws of the families' properties (the properties not listed are
    !! dimensionless: ratios, angles, exponents). Hill muscles: F0 ~ PCSA,
    !! and their damping, proportional to F0 (F0 item), gets lambda_t /
    !! lambda_L from M2 to end at N s/m. Ligaments: L1 and L2 by the force
    !! law, LENGTH stretches their law's elongation axis (l2 by 1/factor^n).
    type(scale_law_t), parameter :: laws(*) = [ &
        scale_law_t('DISCS', 'LENGTH', 0, 1, 0, 'geometry A, h, I, J'), &
        scale_law_t('DISCS', 'E', 1, 0, 0, 'modulus [Pa]'), &
        scale_law_t('DISCS', 'G', 1, 0, 0, 'modulus [Pa]'), &
        scale_law_t('DISCS', 'VISCOUS', 1, 0, 1, 'viscous modulus [Pa s]'), &
        scale_law_t('LIGAMENTS', 'LENGTH', 0, 1, 0, 'elongation axis [m]'), &
        scale_law_t('LIGAMENTS', 'L1', 1, 2, 0, 'force [N]'), &
        scale_law_t('LIGAMENTS', 'L2', 1, 2, 0, 'force [N]'), &
        scale_law_t('MUSCLES', 'LENGTH', 0, 1, 0, 'fibre length [m]'), &
        scale_law_t('MUSCLES', 'F0', 1, 2, 0, 'force [N] (PCSA)'), &
        scale_law_t('MUSCLES', 'M2', 0, -1, 1, 'damping / F0 [s/m]'), &
        scale_law_t('MUSCLES', 'M1', 1, 1, 0, 'stiffness [N/m]'), &
        scale_law_t('LIMITS', 'ROMK', 1, 3, 0, 'stiffness [N m/rad]'), &
        scale_law_t('LIMITS', 'C0', 1, 3, 1, 'damping [N m s/rad]'), &
        scale_law_t('LIMITS', 'C1', 1, 3, 1, 'damping [N m s/rad]'), &
        scale_law_t('NZSPRINGS', 'M0', 1, 3, 0, 'moment [N m]'), &
        scale_law_t('NZSPRINGS', 'MLIN', 1, 3, 0, 'moment [N m]'), &
        scale_law_t('SPRINGS', 'K', 1, 1, 0, 'stiffness [N/m]'), &
        scale_law_t('SPRINGS', 'C', 1, 1, 1, 'damping [N s/m]')]

    !> The scale factors of one occupant and those derived from them.
    type :: occupant_scales_t
        character(len=6) :: code = 'H50M'
        real(wp) :: length = one, mass = one, modulus = one
        real(wp) :: time = one      !! lambda_t = lambda_L sqrt(lambda_m / (lambda_E lambda_L^3))
        real(wp) :: force = one     !! lambda_E lambda_L^2
        real(wp) :: moment = one    !! lambda_E lambda_L^3
        real(wp) :: inertia = one   !! lambda_m lambda_L^2
    end type occupant_scales_t

contains

    !> Place of size `code` in `sizes`, 0 when none is.
    pure integer function size_index(code) result(k)
        character(len=*), intent(in) :: code   !! H05F, H50M, H95M
        k = findloc(sizes%code, code, dim=1)
    end function size_index

    !> The factors of lengths, masses and modulus and those derived from them.
    pure function occupant_scales(code, lambda_l, lambda_m, lambda_e) result(s)
        character(len=*), intent(in) :: code   !! the size's code (for the notes)
        real(wp), intent(in) :: lambda_l        !! lengths
        real(wp), intent(in) :: lambda_m        !! masses
        real(wp), intent(in) :: lambda_e        !! elastic modulus
        type(occupant_scales_t) :: s
        s%code = code
        s%length = lambda_l
        s%mass = lambda_m
        s%modulus = lambda_e
        s%time = lambda_l*sqrt(lambda_m/(lambda_e*lambda_l**3))
        s%force = lambda_e*lambda_l**2
        s%moment = lambda_e*lambda_l**3
        s%inertia = lambda_m*lambda_l**2
    end function occupant_scales

    !> The factor of law `law`: lambda_E^pe lambda_L^pl lambda_t^pt.
    pure real(wp) function law_factor(s, law) result(f)
        type(occupant_scales_t), intent(in) :: s   !! the occupant's factors
        type(scale_law_t), intent(in) :: law       !! the law
        f = s%modulus**law%pe*s%length**law%pl*s%time**law%pt
    end function law_factor

    !> Scale the bodies: masses, inertias, joint points and neutral
    !! translations (the tree's derived tables rebuilt).
    pure subroutine scale_tree(model, s, stat, errmsg)
        type(model_t), intent(inout) :: model          !! the model; out: its tree scaled
        type(occupant_scales_t), intent(in) :: s       !! the occupant's factors
        integer, intent(out) :: stat                   !! 0, or tree_build's status
        character(len=msglen), intent(out) :: errmsg   !! tree_build's message
        model%tree%mass = s%mass*model%tree%mass
        model%tree%inertia = s%inertia*model%tree%inertia
        model%tree%joint_parent = s%length*model%tree%joint_parent
        model%tree%joint_child = s%length*model%tree%joint_child
        model%tree%q_ref(1:3, :) = s%length*model%tree%q_ref(1:3, :)
        call tree_build(model%tree, stat, errmsg)
    end subroutine scale_tree

    !> Scale every property of `laws` of the model's families.
    pure subroutine scale_families(model, s)
        type(model_t), intent(inout) :: model          !! the model; out: its elements' properties scaled
        type(occupant_scales_t), intent(in) :: s       !! the occupant's factors
        integer :: k, fam
        do k = 1, size(laws)
            fam = family_index(laws(k)%family)
            if (fam == 0) cycle
            if (.not. any(family_items(fam) == laws(k)%item)) cycle
            call scale_family(model, fam, laws(k)%item, law_factor(s, laws(k)))
        end do
    end subroutine scale_families

    !> The OCCUPANT card's factors (no card: the 50th male, identity).
    subroutine read_occupant(rd, cards, s, line)
        type(deck_reader_t), intent(inout) :: rd         !! the deck (errors located there)
        type(card_t), intent(in) :: cards(:)             !! the deck's cards
        type(occupant_scales_t), intent(out) :: s        !! the factors
        integer, intent(out) :: line                     !! the card image (0: no card)
        character(len=6) :: code
        real(wp) :: ll, lm, le
        integer :: k
        character(len=6), allocatable :: codes(:)
        line = 0
        do k = size(cards), 1, -1       ! (a loop: no temporary of the key component)
            if (cards(k)%key == 'OCCUPANT') exit
        end do
        if (k == 0) return
        line = cards(k)%first
        codes = [character(len=6) :: sizes%code, 'SCALED']
        call rd%choice(line, 1, 'occupant size', codes, code)
        if (rd%failed()) return
        k = size_index(code)
        if (k > 0) then
            call rd%real(line, 2, 'length factor lambda_L', '-', ll, 0.3_wp, 3.0_wp, default=sizes(k)%lambda_l)
            call rd%real(line, 3, 'mass factor lambda_m', '-', lm, 0.03_wp, 30.0_wp, default=sizes(k)%lambda_m)
            call rd%real(line, 4, 'modulus factor lambda_E', '-', le, 0.1_wp, 10.0_wp, default=sizes(k)%lambda_e)
        else
            call rd%real(line, 2, 'length factor lambda_L', '-', ll, 0.3_wp, 3.0_wp)
            if (rd%failed()) return
            call rd%real(line, 3, 'mass factor lambda_m', '-', lm, 0.03_wp, 30.0_wp, default=ll**3)
            call rd%real(line, 4, 'modulus factor lambda_E', '-', le, 0.1_wp, 10.0_wp, default=one)
        end if
        if (rd%failed()) return
        s = occupant_scales(code, ll, lm, le)
    end subroutine read_occupant

    !> OCCUPANT, with the bodies (after MERGE): the tree scaled, the factor
    !! on the elements' points set, the criteria's occupant chosen and a note.
    subroutine occupant_bodies(rd, cards, cs, bmap)
        type(deck_reader_t), intent(inout) :: rd   !! the deck (errors located there)
        type(card_t), intent(in) :: cards(:)       !! the deck's cards
        type(case_t), intent(inout) :: cs          !! the case; out: tree scaled, occupant, note
        type(body_map_t), intent(inout) :: bmap    !! out: its length factor
        type(occupant_scales_t) :: s
        integer :: line, stat
        character(len=msglen) :: msg
        call read_occupant(rd, cards, s, line)
        if (rd%failed() .or. line == 0) return
        call scale_tree(cs%model, s, stat, msg)
        if (stat /= 0) then
            call rd%fail(rd%where(line)//' (OCCUPANT card): '//trim(msg))
            return
        end if
        bmap%length = s%length
        if (occupant_index(s%code(1:4)) > 0 .and. s%code /= 'SCALED') cs%occupant = s%code(1:4)
        cs%changes = [character(len=160) :: cs%changes, 'OCCUPANT '//trim(s%code)//': lengths x'// &
                      trim(adjustl(field_text(s%length)))//', masses x'//trim(adjustl(field_text(s%mass)))// &
                      ', modulus x'//trim(adjustl(field_text(s%modulus)))//', time x'// &
                      trim(adjustl(field_text(s%time)))//', forces x'//trim(adjustl(field_text(s%force)))// &
                      '  ('//trim(rd%where(line))//')']
    end subroutine occupant_bodies

    !> OCCUPANT, after the element cards: the families' properties scaled.
    subroutine occupant_elements(rd, cards, cs)
        type(deck_reader_t), intent(inout) :: rd   !! the deck (errors located there)
        type(card_t), intent(in) :: cards(:)       !! the deck's cards
        type(case_t), intent(inout) :: cs          !! the case; out: its elements scaled
        type(occupant_scales_t) :: s
        integer :: line
        call read_occupant(rd, cards, s, line)
        if (rd%failed() .or. line == 0) return
        call scale_families(cs%model, s)
    end subroutine occupant_elements

end module hn_occupant
