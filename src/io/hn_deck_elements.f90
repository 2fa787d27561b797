!> The element cards of a deck, the cards of the element families
!! (hn_families): DISC, LIGAMENT, MUSCLE, HILL, VIA, ACTIVATE, LIMIT, ROM,
!! SPRING, and SCALE and FAMILY, which act on a family (`element_cards`).
module hn_deck_elements
    use hn_kinds, only: wp, zero, one, deg, g_std
    use hn_case, only: case_t
    use hn_deck_reader, only: deck_reader_t, int_str
    use hn_model, only: family_items, family_items_text, scale_family, max_family_items, model_set_family
    use hn_families, only: nfamilies, family_name, family_index, fam_discs, fam_ligaments, fam_muscles, fam_limits, &
                           fam_springs
    use hn_disc_family, only: disc_family_t
    use hn_ligament_family, only: ligament_family_t
    use hn_muscle_family, only: muscle_family_t
    use hn_limit_family, only: limit_family_t
    use hn_spring_family, only: spring_family_t
    use hn_motion, only: motion_eval
    use hn_discs, only: disc_t
    use hn_line_elements, only: line_attach_t, ligament_t, muscle_t, spring_t, muscle_hill, max_via
    use hn_muscle, only: activation_t
    use hn_joint_limits, only: joint_limit_t, joint_range_t
    use hn_rotation, only: norm3
    use hn_deck_state, only: deck_state_t, coord_names, big_length, big_modulus, card_t, body_map_t, add_scene_note, &
                             active_ref, family_ref, body_ref, table_ref, unit_of, unit_factor, unit_limit, join
    implicit none
    private

    public :: element_cards, disc_card, joint_card, scale_card, family_card, activation_cards

contains

    !> DISC, LIGAMENT, MUSCLE, LIMIT, SPRING, FAMILY cards. Elements are
    !! moved onto merged bodies; an element inside one merged body, or a
    !! joint damper on a locked or merged coordinate, is dropped.
    subroutine element_cards(rd, st, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(deck_state_t), intent(in) :: st  !! the deck's cards, bodies (names, where each went) and tables
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        integer :: k, i, ninternal, nlimdrop, it
        integer :: nel(nfamilies)       !! elements so far of each family
        integer :: njoint(2)            !! joint-limit dampers and ranges of motion so far
        logical :: keep
        type(disc_family_t) :: df
        type(ligament_family_t) :: lf
        type(muscle_family_t) :: mf
        type(limit_family_t) :: jf
        type(spring_family_t) :: sf
        type(disc_t) :: d
        character(len=100) :: note
        type(ligament_t) :: g
        type(muscle_t) :: mu
        type(spring_t) :: sp

        ninternal = 0
        nlimdrop = 0
        call activation_cards(rd, st%cards, cs, mf%activations)
        if (rd%failed()) return
        ! room for every element card, trimmed at the end (appending one by one is quadratic)
        allocate (df%items(count(st%cards%key == 'DISC')), lf%items(count(st%cards%key == 'LIGAMENT')), &
                  mf%items(count(st%cards%key == 'MUSCLE' .or. st%cards%key == 'HILL')), &
                  sf%items(count(st%cards%key == 'SPRING')), jf%items(count(st%cards%key == 'LIMIT')), &
                  jf%ranges(count(st%cards%key == 'ROM')), mf%tables(0))
        nel = 0
        njoint = 0
        do k = 1, size(st%cards)
            i = st%cards(k)%first
            select case (st%cards(k)%key)
            case ('DISC')
                call disc_card(rd, i, st%bnames, st%bmap, ninternal, d, keep)
                if (keep) call append(fam_discs)
            case ('LIGAMENT')
                g = ligament_t()
                call line_card(rd, i, 'ligament', g%line_attach_t, i, 7, keep)
                call rd%real(i, 4, 'l1', 'N/m', g%l1, zero, big_modulus)
                call rd%real(i, 5, 'l2', 'N/m^n', g%l2, zero, 1.0e30_wp)
                call rd%real(i, 6, 'exponent n', '-', g%n, one, 10.0_wp, default=2.0_wp)
                if (keep .and. .not. rd%failed()) call append(fam_ligaments)
            case ('MUSCLE')
                mu = muscle_t()
                call line_card(rd, i, 'muscle', mu%line_attach_t, i + 1, 7, keep)
                call rd%real(i, 4, 'stiffness m1', 'N/m', mu%m1, zero, big_modulus)
                call rd%real(i, 5, 'damping m2', 'N s/m', mu%m2, zero, big_modulus)
                call rd%real(i, 6, 'active force Fmax', 'N', mu%fmax, zero, 1.0e6_wp, default=zero)
                if (.not. rd%is_blank(i, 7)) then
                    it = table_ref(rd, i, 7, st%tabs)
                    if (.not. rd%failed()) then
                        mf%tables = [mf%tables, st%tabs(it)%tab]
                        mu%activation = size(mf%tables)
                    end if
                end if
                if (keep .and. .not. rd%failed()) call append(fam_muscles)
            case ('HILL')
                mu = muscle_t(law=muscle_hill)
                call line_card(rd, i, 'muscle', mu%line_attach_t, i + 1, 7, keep)
                call rd%real(i, 4, 'maximum isometric force F0', 'N', mu%hill%f0, zero, 1.0e5_wp)
                call rd%real(i, 5, 'optimal fibre length', 'm', mu%hill%lopt, 1.0e-3_wp, one)
                if (.not. rd%is_blank(i, 6)) mu%history = history_ref(rd, i, 6, mf%activations)
                if (mu%history > 0) then
                    mu%hill%srs_q = mf%activations(mu%history)%srs_q
                    mu%hill%srs_range = mf%activations(mu%history)%srs_range
                end if
                call rd%real(i, 7, 'damping', 'N s/m', mu%hill%damping, zero, 1.0e5_wp, default=zero)
                if (keep .and. .not. rd%failed()) call append(fam_muscles)
            case ('SPRING')
                sp = spring_t()
                call line_card(rd, i, 'spring', sp%line_attach_t, i, 6, keep)
                call rd%real(i, 4, 'stiffness', 'N/m', sp%stiffness, zero, big_modulus)
                call rd%real(i, 5, 'damping', 'N s/m', sp%damping, zero, big_modulus, default=zero)
                if (keep .and. .not. rd%failed()) call append(fam_springs)
            case ('LIMIT', 'ROM')
                call joint_card(rd, i, cs, st%bnames, st%bmap, nlimdrop, jf, njoint)
            case ('FAMILY')
                call family_card(rd, i, cs)
            end select
            if (rd%failed()) return
        end do
        df%items = df%items(1:nel(fam_discs))
        lf%items = lf%items(1:nel(fam_ligaments))
        mf%items = mf%items(1:nel(fam_muscles))
        jf%items = jf%items(1:njoint(1))
        jf%ranges = jf%ranges(1:njoint(2))
        sf%items = sf%items(1:nel(fam_springs))
        if (ninternal > 0) then
            write (note, '(i0,a)') ninternal, ' ELEMENTS DROPPED: BOTH ENDS ON ONE MERGED BODY'
            call add_scene_note(cs, note)
        end if
        if (nlimdrop > 0) then
            write (note, '(i0,a)') nlimdrop, ' JOINT-LIMIT DAMPERS DROPPED: ON LOCKED OR MERGED COORDINATES'
            call add_scene_note(cs, note)
        end if
        do k = 1, size(st%cards)
            if (st%cards(k)%key == 'VIA') call via_card(rd, st%cards, st%cards(k)%first, mf%items, st%bnames, st%bmap)
            if (rd%failed()) return
        end do
        call model_set_family(cs%model, fam_discs, df)
        call model_set_family(cs%model, fam_ligaments, lf)
        call model_set_family(cs%model, fam_muscles, mf)
        call model_set_family(cs%model, fam_limits, jf)
        call model_set_family(cs%model, fam_springs, sf)
        do k = 1, size(st%cards)
            if (st%cards(k)%key == 'SCALE') call scale_card(rd, st%cards(k)%first, cs)
            if (rd%failed()) return
        end do
    contains
        !> Put the element just read into place nel(f) + 1 of family f's list.
        subroutine append(f)
            integer, intent(in) :: f
            nel(f) = nel(f) + 1
            select case (f)
            case (fam_discs); df%items(nel(f)) = d
            case (fam_ligaments); lf%items(nel(f)) = g
            case (fam_muscles); mf%items(nel(f)) = mu
            case (fam_springs); sf%items(nel(f)) = sp
            end select
        end subroutine append

        !> The attachment of a LIGAMENT, MUSCLE or SPRING card: name (F1),
        !! bodies (F2, F3), points (first continuation card, F1-F6) and free
        !! length (line ll, field lf; blank: the neutral length), moved onto
        !! merged bodies; keep is false for an element inside one merged body.
        subroutine line_card(rd, i, what, at, ll, lf, keep)
            type(deck_reader_t), intent(inout) :: rd
            integer, intent(in) :: i, ll, lf
            character(len=*), intent(in) :: what
            type(line_attach_t), intent(inout) :: at
            logical, intent(out) :: keep
            character(len=10) :: nm
            keep = .false.
            call rd%name(i, 1, what//' name', nm)
            at%name = nm
            at%body_a = body_ref(rd, i, 2, 'body a', st%bnames, .true.)
            at%body_b = body_ref(rd, i, 3, 'body b', st%bnames, .true.)
            call distinct_bodies(rd, i, at%body_a, at%body_b)
            call line_points(rd, i + 1, at%point_a, at%point_b)
            select case (what)
            case ('ligament')
                call rd%real(ll, lf, 'slack length', 'm', at%length0, 1.0e-6_wp, big_length, default=-one)
            case ('muscle')
                call rd%real(ll, lf, 'rest length', 'm', at%length0, 1.0e-6_wp, big_length, default=-one)
            case default
                call rd%real(ll, lf, 'free length', 'm', at%length0, zero, big_length, default=-one)
            end select
            if (rd%failed()) return
            call map_ends(st%bmap, at%body_a, at%point_a, at%body_b, at%point_b, ninternal)
            keep = at%body_a /= at%body_b
        end subroutine line_card
    end subroutine element_cards

    !> VIA muscle body x y z: the next via point of a muscle's path (MUSCLE or
    !! HILL card of that name), in order from body a to body b, moved onto
    !! a merged body as the muscle's ends are; a VIA card of a muscle the
    !! scene dropped is dropped with it.
    subroutine via_card(rd, cards, i, muscles, bnames, bmap)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        integer, intent(in) :: i
        type(muscle_t), intent(inout) :: muscles(:)
        character(len=10), intent(in) :: bnames(:)
        type(body_map_t), intent(in) :: bmap
        character(len=10) :: nm, other
        real(wp) :: p(3)
        integer :: e, kb, f, k
        logical :: defined
        call rd%name(i, 1, 'muscle name', nm)
        kb = body_ref(rd, i, 2, 'body', bnames, .true.)
        do f = 1, 3
            call rd%real(i, 2 + f, 'via point', 'm', p(f), -big_length, big_length)
        end do
        if (rd%failed()) return
        do e = size(muscles), 1, -1       ! (a loop: no temporary of the name component)
            if (muscles(e)%name == nm) exit
        end do
        if (e == 0) then
            defined = .false.
            do k = 1, size(cards)
                if (cards(k)%key /= 'MUSCLE' .and. cards(k)%key /= 'HILL') cycle
                call rd%name(cards(k)%first, 1, 'muscle name', other)
                defined = defined .or. other == nm
            end do
            if (.not. defined) call rd%fail(rd%context(i, 1, 'muscle name')//': found "'//trim(nm)// &
                                            '"; expected the name of a MUSCLE or HILL card')
            return
        end if
        associate (m => muscles(e))
            if (m%nvia == max_via) then
                call rd%fail(rd%context(i, 1, 'muscle name')//': muscle "'//trim(nm)//'" has '// &
                             trim(int_str(max_via))//' via points already; expected at most '// &
                             trim(int_str(max_via))//' VIA cards per muscle')
                return
            end if
            if (kb > 0) then
                p = p + bmap%shift(:, kb)
                kb = bmap%new(kb)
            end if
            m%nvia = m%nvia + 1
            m%via_body(m%nvia) = kb
            m%via_point(:, m%nvia) = p
        end associate
    end subroutine via_card

    !> ACTIVATE cards: the activation histories of Hill-type muscles. A blank
    !! onset is the sled pulse onset: the first time the prescribed
    !! translational acceleration of the root body exceeds 1 g (never, when
    !! it does not).
    subroutine activation_cards(rd, cards, cs, activations)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(card_t), intent(in) :: cards(:)  !! the deck's cards with their continuation cards (group_cards)
        type(case_t), intent(in) :: cs  !! the run case the cards fill
        type(activation_t), allocatable, intent(out) :: activations(:)  !! the activation histories (ACTIVATE cards), in deck order
        type(activation_t) :: ah
        integer :: k, i
        allocate (activations(0))
        do k = 1, size(cards)
            if (cards(k)%key /= 'ACTIVATE') cycle
            i = cards(k)%first
            ah = activation_t()
            call rd%name(i, 1, 'history name', ah%name)
            if (rd%failed()) return
            call rd%real(i, 2, 'pre-activation u0', '-', ah%u0, zero, one)
            call rd%real(i, 3, 'reflex activation u1', '-', ah%u1, zero, one)
            if (rd%is_blank(i, 4)) then
                ah%t_onset = pulse_onset(cs)
            else
                call rd%real(i, 4, 'pulse onset', 's', ah%t_onset, -1.0e4_wp, 1.0e4_wp)
            end if
            call rd%real(i, 5, 'reflex delay', 's', ah%delay, zero, 10.0_wp)
            call rd%real(i, 6, 'rise time', 's', ah%rise, zero, 10.0_wp, default=zero)
            call rd%real(i + 1, 1, 'activation time constant', 's', ah%tau_act, 1.0e-4_wp, 10.0_wp, default=0.015_wp)
            call rd%real(i + 1, 2, 'deactivation time constant', 's', ah%tau_deact, 1.0e-4_wp, 10.0_wp, &
                         default=0.05_wp)
            call rd%real(i + 1, 3, 'short-range stiffness q', '-', ah%srs_q, zero, 1.0e3_wp, default=zero)
            call rd%real(i + 1, 4, 'short-range stiffness range', 'lopt', ah%srs_range, 1.0e-4_wp, one, &
                         default=0.01_wp)
            if (rd%failed()) return
            activations = [activations, ah]
        end do
    end subroutine activation_cards

    !> First time (on a 0.1 ms grid) the prescribed translational
    !! acceleration of the root body exceeds 1 g; huge when it never does.
    function pulse_onset(cs) result(t0)
        type(case_t), intent(in) :: cs
        real(wp) :: t0, t, a(3), x, xd
        integer :: root, m, j, n
        t0 = huge(one)
        root = findloc(cs%model%tree%parent, 0, dim=1)
        do n = 0, nint((cs%t_end - cs%t_start)/1.0e-4_wp)
            t = cs%t_start + n*1.0e-4_wp
            a = zero
            do m = 1, 3
                j = cs%model%tree%dof_index(m, root)
                if (j == 0) cycle
                if (cs%model%prescribed(j)) call motion_eval(cs%model%motion(j), t, x, xd, a(m))
            end do
            if (norm3(a) > g_std) then
                t0 = t
                return
            end if
        end do
    end function pulse_onset

    !> Activation history named in field f (an ACTIVATE card).
    integer function history_ref(rd, i, f, hist) result(ih)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i, f
        type(activation_t), intent(in) :: hist(:)
        character(len=10) :: s
        ih = 0
        call rd%name(i, f, 'activation history', s)
        if (rd%failed()) return
        do ih = size(hist), 1, -1
            if (hist(ih)%name == s) exit
        end do
        if (ih == 0) call rd%fail(rd%context(i, f, 'activation history')//': found "'//trim(s)// &
                                  '"; expected the name of an ACTIVATE card')
    end function history_ref

    !> Old body numbers and points -> reduced tree (MERGE); counts the
    !! elements with both ends on one merged body.
    pure subroutine map_ends(bmap, ka, pa, kb, pb, ninternal)
        type(body_map_t), intent(in) :: bmap
        integer, intent(inout) :: ka, kb
        real(wp), intent(inout) :: pa(3), pb(3)
        integer, intent(inout) :: ninternal
        if (ka > 0) then
            pa = pa + bmap%shift(:, ka)
            ka = bmap%new(ka)
        end if
        if (kb > 0) then
            pb = pb + bmap%shift(:, kb)
            kb = bmap%new(kb)
        end if
        if (ka == kb) ninternal = ninternal + 1
    end subroutine map_ends

    !> A DISC card and its two continuation cards; keep is false for a disc
    !! inside one merged body.
    subroutine disc_card(rd, i, bnames, bmap, ninternal, d, keep)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        character(len=10), intent(in) :: bnames(:)  !! the names of the deck's bodies, in deck order
        type(body_map_t), intent(in) :: bmap  !! where each deck body went (MERGE), what locked its coordinates
        integer, intent(inout) :: ninternal  !! elements so far with both ends on one merged body
        type(disc_t), intent(out) :: d  !! the disc
        logical, intent(out) :: keep  !! false for a disc inside one merged body
        integer :: f
        real(wp) :: v
        d = disc_t()
        call rd%name(i, 1, 'disc name', d%name)
        d%body_a = body_ref(rd, i, 2, 'lower body', bnames, .false.)
        d%body_b = body_ref(rd, i, 3, 'upper body', bnames, .false.)
        call distinct_bodies(rd, i, d%body_a, d%body_b)
        call rd%real(i, 4, 'area A', 'm^2', d%area, 1.0e-8_wp, 1.0_wp)
        call rd%real(i, 5, 'thickness h', 'm', d%h, 1.0e-5_wp, 1.0_wp)
        call rd%real(i, 6, 'modulus d1', 'Pa', d%d1, 1.0e-3_wp, big_modulus)
        call rd%real(i, 7, 'viscous modulus d2', 'Pa s', d%d2, zero, big_modulus)
        do f = 1, 3
            call rd%real(i + 1, f, 'lower plate centre', 'm', d%pa(f), -big_length, big_length)
            call rd%real(i + 1, 3 + f, 'upper plate centre', 'm', d%pb(f), -big_length, big_length)
        end do
        call rd%real(i + 1, 7, 'plate tilt', 'deg', v, -90.0_wp, 90.0_wp, default=zero)
        d%tilt = v*deg
        call rd%real(i + 2, 1, 'shear modulus G', 'Pa', d%g, 1.0e-3_wp, big_modulus)
        call rd%real(i + 2, 2, 'second moment Ix', 'm^4', d%ix, 1.0e-20_wp, one)
        call rd%real(i + 2, 3, 'second moment Iy', 'm^4', d%iy, 1.0e-20_wp, one)
        call rd%real(i + 2, 4, 'torsion constant J', 'm^4', d%j, 1.0e-20_wp, one)
        call rd%real(i + 2, 5, 'shear factor k', '-', d%kshear, 0.1_wp, 10.0_wp, default=1.2_wp)
        call rd%real(i + 2, 6, 'viscous modulus d2b of shear, bending and torsion', 'Pa s', d%d2b, zero, &
                     big_modulus, default=d%d2)
        call rd%real(i + 2, 7, 'axial stiffness in tension as a fraction of d1''s', '-', d%ft, 1.0e-3_wp, one, &
                     default=one)
        if (rd%failed()) return
        call map_ends(bmap, d%body_a, d%pa, d%body_b, d%pb, ninternal)
        keep = d%body_a /= d%body_b
    end subroutine disc_card

    !> A LIMIT card (one-way joint-limit damper) or a ROM card (resistance
    !! beyond the physiological range: rotation, range (deg), stiffness at the
    !! edge K [N m/rad], excess t0 [deg] over which it grows e-fold); dropped
    !! on a locked or merged coordinate.
    subroutine joint_card(rd, i, cs, bnames, bmap, ndrop, jf, nel)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        character(len=10), intent(in) :: bnames(:)  !! the names of the deck's bodies, in deck order
        type(body_map_t), intent(in) :: bmap  !! where each deck body went (MERGE), what locked its coordinates
        integer, intent(inout) :: ndrop  !! dampers dropped so far (on locked or merged coordinates)
        type(limit_family_t), intent(inout) :: jf     !! the dampers and ranges read so far
        integer, intent(inout) :: nel(2)              !! how many dampers and ranges
        type(joint_limit_t) :: lim
        type(joint_range_t) :: r
        integer :: kb, m, j
        ! a body absorbed by MERGE or a locked coordinate: the element would do nothing
        if (bmap%merged_by(body_ref(rd, i, 1, 'body', bnames, .false.)) > 0) then
            ndrop = ndrop + 1
            return
        end if
        call active_ref(rd, i, cs, bnames, bmap, kb, m, j, .true.)
        if (rd%failed()) return
        if (j == 0) then
            ndrop = ndrop + 1
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
                         default=max(lim%xmin, min(lim%xmax, cs%model%tree%q_ref(m, kb)/unit_factor(m))))
            lim%xmin = lim%xmin*unit_factor(m)
            lim%xmax = lim%xmax*unit_factor(m)
            lim%xneutral = lim%xneutral*unit_factor(m)
            if (rd%failed()) return
            nel(1) = nel(1) + 1; jf%items(nel(1)) = lim
            return
        end if
        if (m <= 3) then
            call rd%fail(rd%context(i, 2, 'coordinate')//': found '//coord_names(m)//'; expected a rotation '// &
                         '(RX, RY or RZ): ROM cards hold joint rotations')
            return
        end if
        r%dof = j
        r%label = trim(cs%model%tree%name(kb))//' '//coord_names(m)
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
        nel(2) = nel(2) + 1; jf%ranges(nel(2)) = r
    end subroutine joint_card

    !> SCALE name family item factor: multiply one property of every element
    !! of a family (the items of a sweep's FAMILY parameters), after every
    !! element card; the named factors a calibration fits (FIELD4 SCALE name).
    subroutine scale_card(rd, i, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        character(len=10) :: s, item, items(max_family_items)
        integer :: fam
        real(wp) :: factor
        call rd%name(i, 1, 'factor name', s)
        call rd%name(i, 2, 'element family', s)
        fam = family_ref(rd, i, s)
        if (rd%failed()) return
        call rd%name(i, 3, 'item', item)
        items = family_items(fam)
        if (.not. rd%failed() .and. .not. any(items == item .and. len_trim(items) > 0)) then
            call rd%fail(rd%context(i, 3, 'item')//': found "'//trim(item)//'"; expected '//family_items_text(fam))
            return
        end if
        call rd%real(i, 4, 'factor', '-', factor, 1.0e-6_wp, 1.0e6_wp)
        if (rd%failed()) return
        call scale_family(cs%model, fam, item, factor)
    end subroutine scale_card

    !> FAMILY name ON|OFF: switch an element family.
    subroutine family_card(rd, i, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        integer :: fam
        character(len=10) :: s
        character(len=100) :: note
        call rd%name(i, 1, 'element family', s)
        if (rd%failed()) return
        fam = family_index(s)
        if (fam == 0) then
            call rd%fail(rd%context(i, 1, 'element family')//': found "'// &
                         trim(s)//'"; expected one of '//join(family_name))
            return
        end if
        call rd%name(i, 2, 'ON or OFF', s)
        if (s /= 'ON' .and. s /= 'OFF' .and. .not. rd%failed()) then
            call rd%fail(rd%context(i, 2, 'ON or OFF')//': found "'//trim(s)// &
                         '"; expected ON or OFF')
            return
        end if
        cs%model%family_on(fam) = s == 'ON'
        if (s == 'OFF') then
            note = 'FAMILY '//trim(family_name(fam))//' OFF'
            call add_scene_note(cs, note)
        end if
    end subroutine family_card

    !> Attachment points on a continuation card: F1-F3 on body a, F4-F6 on body b.
    subroutine line_points(rd, i, pa, pb)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i
        real(wp), intent(out) :: pa(3), pb(3)
        integer :: f
        do f = 1, 3
            call rd%real(i, f, 'point on body a', 'm', pa(f), -big_length, big_length)
            call rd%real(i, 3 + f, 'point on body b', 'm', pb(f), -big_length, big_length)
        end do
    end subroutine line_points

    subroutine distinct_bodies(rd, i, ka, kb)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i, ka, kb
        if (rd%failed()) return
        if (ka == kb) call rd%fail(rd%where(i)//', columns 21-40 ('//trim(rd%key(i))//' card, fields F2-F3): '// &
                                   'both ends on the same body; expected two different bodies')
    end subroutine distinct_bodies

end module hn_deck_elements
