!> The control cards of a deck: TITLE, CONTROL, SOLVER, GRAVITY, OUTPUT,
!! H5FILE, EVENTS, HOLD, DUMP (`control_cards`), HEADNECK, CRITERIA,
!! LOADCELL, PRINT and STATICS (`report_cards`, after the bodies) and RUNLIMIT (`runlimit_card`).
module hn_deck_control
    use hn_kinds, only: wp, zero, one
    use hn_case, only: case_t
    use hn_deck_reader, only: deck_reader_t
    use hn_linsolve, only: solver_cholesky, solver_names, solver_code
    use hn_integrators, only: integrator_names, jacobian_steps_default, factor_band_default, factor_band_max
    use hn_criteria_card, only: criteria_card
    use hn_loadcell_card, only: loadcell_cards
    use hn_print_card, only: print_cards
    use hn_statics_card, only: statics_card
    use hn_deck_state, only: card_t, body_map_t, single, body_ref, join, real_str
    implicit none
    private

    public :: runlimit_card, title_cards, control_cards, report_cards

contains

    !> RUNLIMIT wall steps: stop the run (exit 3, files kept and marked
    !! incomplete) after this wall time [s] or this many steps; blank: no limit.
    subroutine runlimit_card(rd, cards, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(card_t), intent(in) :: cards(:)  !! the deck's cards with their continuation cards (group_cards)
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        integer :: ic
        ic = single(cards, 'RUNLIMIT')
        if (ic == 0 .or. rd%failed()) return
        call rd%real(cards(ic)%first, 1, 'wall-time limit', 's', cs%wall_limit, 1.0e-3_wp, 1.0e7_wp, default=zero)
        call rd%int(cards(ic)%first, 2, 'step limit', cs%step_limit, 1, huge(1), default=0)
        if (.not. rd%failed() .and. cs%wall_limit <= zero .and. cs%step_limit == 0) &
            call rd%fail(rd%where(cards(ic)%first)//', columns 11-30 (RUNLIMIT card): found no limit; '// &
                         'expected a wall time [s] in F1, a step count in F2, or both')
    end subroutine runlimit_card

    !> TITLE: the deck's first card is its title. A deck that INCLUDEs a
    !! case deck (a variant of it) meets that deck's TITLE too: the TITLE
    !! card of an INCLUDEd file is a subtitle, in deck order (the card
    !! engine refused a second TITLE card in one file).
    subroutine title_cards(rd, cards, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(card_t), intent(in) :: cards(:)  !! the deck's cards with their continuation cards (group_cards)
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        integer :: k
        logical :: first
        first = .true.
        do k = 1, size(cards)
            if (cards(k)%key /= 'TITLE') cycle
            if (first) then
                cs%model%title = rd%text(cards(k)%first, 11)
            else
                cs%subtitles = [character(len=80) :: cs%subtitles, rd%text(cards(k)%first, 11)]
            end if
            first = .false.
        end do
        if (first) call rd%fail(rd%top//': the deck has no TITLE card; expected one')
    end subroutine title_cards

    !> TITLE, CONTROL, SOLVER, GRAVITY, OUTPUT, H5FILE, DUMP, HOLD.
    subroutine control_cards(rd, cards, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(card_t), intent(in) :: cards(:)  !! the deck's cards with their continuation cards (group_cards)
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        integer :: ic, i, k, f, nd
        character(len=10) :: s
        real(wp) :: v, span
        real(wp), allocatable :: tmp(:)

        call title_cards(rd, cards, cs)
        if (rd%failed()) return

        ic = single(cards, 'CONTROL')
        if (rd%failed() .or. ic == 0) return     ! (the card engine refused a deck without one)
        i = cards(ic)%first
        call rd%real(i, 7, 'start time', 's', cs%t_start, -1.0e4_wp, 1.0e4_wp, default=zero)
        call rd%real(i, 1, 'end time', 's', cs%t_end, -1.0e4_wp, 1.0e4_wp)
        if (.not. rd%failed() .and. .not. (cs%t_end > cs%t_start)) then
            call rd%fail(rd%context(i, 1, 'end time')//': found '// &
                         trim(rd%raw(i, 1))//' s; expected an end time after the start time '// &
                         trim(real_str(cs%t_start))//' s')
            return
        end if
        span = cs%t_end - cs%t_start
        call rd%real(i, 2, 'step', 's', cs%h, 1.0e-12_wp, 1.0e4_wp)
        if (rd%failed()) return
        cs%control_at = rd%context(i, 2, 'step')
        if (span/cs%h > 1.0e8_wp) then
            call rd%fail(rd%context(i, 2, 'step')//': found '// &
                         trim(rd%raw(i, 2))//' s; a step this small needs more than 1E8 steps for the run; '// &
                         'expected a step of at least '//trim(real_str(span*1.0e-8_wp))//' s')
            return
        end if
        if (cs%h > span) then
            call rd%fail(rd%context(i, 2, 'step')//': found '// &
                         trim(rd%raw(i, 2))//' s; expected a step no longer than the run ('// &
                         trim(real_str(span))//' s)')
            return
        end if
        call rd%real(i, 3, 'print interval', 's', cs%print_dt, 1.0e-9_wp, 1.0e4_wp)
        if (rd%failed()) return
        if (span/cs%print_dt > 1.0e6_wp) then
            call rd%fail(rd%context(i, 3, 'print interval')//': found '// &
                         trim(rd%raw(i, 3))//' s; expected at most 1E6 print times in the run')
            return
        end if
        call rd%name(i, 4, 'integrator', s)
        if (.not. rd%failed()) then
            if (.not. any(integrator_names == s(1:8))) then
                call rd%fail(rd%context(i, 4, 'integrator')//': found "'// &
                             trim(s)//'"; expected one of '//join(integrator_names))
                return
            end if
            cs%integrator = s(1:8)
        end if
        call rd%real(i, 5, 'relative tolerance', '-', cs%rtol, 1.0e-14_wp, 0.1_wp, default=1.0e-6_wp)
        call rd%real(i, 6, 'absolute tolerance', '-', cs%atol, 1.0e-16_wp, 1.0_wp, default=1.0e-8_wp)
        if (rd%failed()) return

        ! SOLVER: how a_ij xddot = f is solved (default CHOLESKY: a_ij and f_i by
        ! the recursive forms) and the Jacobian of the stiff integrators
        ! (default STRUCT: from the elements' tangent; FD: differences)
        cs%model%solver = solver_cholesky
        ic = single(cards, 'SOLVER')
        if (ic > 0) then
            i = cards(ic)%first
            call rd%name(i, 1, 'method', s)
            if (rd%failed()) return
            cs%model%solver = solver_code(trim(s))
            if (cs%model%solver == 0) then
                call rd%fail(rd%context(i, 1, 'method')//': found "'//trim(s)//'"; expected one of '// &
                             join(solver_names))
                return
            end if
            if (len_trim(rd%raw(i, 2)) > 0) then
                call rd%choice(i, 2, 'Jacobian', [character(len=6) :: 'STRUCT', 'FD'], s)
                if (rd%failed()) return
                cs%model%jacobian = s(1:8)
            end if
            ! ROS34PW2's reuse of its Jacobian and factorization
            ! (read as a real: --set writes its values in E format)
            call rd%real(i, 3, 'accepted steps per Jacobian', '-', v, one, 1.0e5_wp, &
                         default=real(jacobian_steps_default, wp))
            if (rd%failed()) return
            if (v /= aint(v)) then
                call rd%fail(rd%context(i, 3, 'accepted steps per Jacobian')//': found '//trim(real_str(v))// &
                             '; expected a whole number')
                return
            end if
            cs%jac_steps = nint(v)
            call rd%real(i, 4, 'step-size band of a factorization', '-', cs%jac_band, one, factor_band_max, &
                         default=factor_band_default)
            if (rd%failed()) return
        end if
        ic = single(cards, 'GRAVITY')
        if (ic > 0) then
            do f = 1, 3
                call rd%real(cards(ic)%first, f, 'gravity component', 'm/s^2', v, -1.0e3_wp, 1.0e3_wp)
                cs%model%gravity(f) = v
            end do
        end if
        cs%sample_dt = min(cs%print_dt, 1.0e-4_wp)
        ic = single(cards, 'OUTPUT')
        if (ic > 0) then
            call rd%real(cards(ic)%first, 1, 'HDF5 sample interval', 's', cs%sample_dt, 1.0e-9_wp, 1.0e4_wp)
            if (rd%failed()) return
            if (span/cs%sample_dt > 1.0e7_wp) &
                call rd%fail(rd%context(cards(ic)%first, 1, 'HDF5 sample interval')// &
                             ': expected at most 1E7 samples in the run')
            if (len_trim(rd%raw(cards(ic)%first, 2)) > 0) then
                call rd%choice(cards(ic)%first, 2, 'output accelerations', [character(len=7) :: 'HERMITE', 'SOLVE'], s)
                if (rd%failed()) return
                cs%output_xdd = s(1:8)
            end if
        end if
        call h5file_card(rd, cards, cs)
        if (rd%failed()) return
        ic = single(cards, 'EVENTS')
        if (ic > 0) then
            call rd%choice(cards(ic)%first, 1, 'event handling', [character(len=5) :: 'NONE', 'TIME', 'STATE'], s)
            cs%events = s(1:8)
        end if
        ic = single(cards, 'HOLD')
        if (ic > 0) call hold_card(rd, cards(ic)%first, cs)
        allocate (cs%dump_times(0))
        do k = 1, size(cards)
            if (cards(k)%key /= 'DUMP') cycle
            i = cards(k)%first
            nd = 0
            do f = 1, 7
                if (rd%is_blank(i, f)) cycle
                call rd%real(i, f, 'dump time', 's', v, cs%t_start, cs%t_end)
                tmp = [cs%dump_times, v]
                call move_alloc(tmp, cs%dump_times)
                nd = nd + 1
            end do
            if (nd == 0 .and. .not. rd%failed()) &
                call rd%fail(rd%where(i)//', columns 11-80 (DUMP card): found no times; expected 1 to 7 times [s]')
        end do
    end subroutine control_cards

    !> The H5FILE card: the result file. One card per file of the deck (the
    !! card engine refused a second in one file); the deck's own card wins
    !! over an INCLUDEd deck's (a variant names its own file), and an
    !! INCLUDEd deck's only is marked h5file_included: a variant's run is
    !! then named after the variant's deck file (hhneck's main).
    subroutine h5file_card(rd, cards, cs)
        type(deck_reader_t), intent(in) :: rd  !! the deck: card images, located field access
        type(card_t), intent(in) :: cards(:)  !! the deck's cards with their continuation cards (group_cards)
        type(case_t), intent(inout) :: cs  !! the run case: h5file, h5file_included
        integer :: k, i, chosen
        chosen = 0
        do k = 1, size(cards)
            if (cards(k)%key /= 'H5FILE') cycle
            i = cards(k)%first
            if (chosen == 0) then
                chosen = i
            else if (rd%lines(i)%via == 0) then
                chosen = i
            end if
        end do
        if (chosen == 0) return
        cs%h5file = rd%text(chosen, 11)
        cs%h5file_included = rd%lines(chosen)%via > 0
    end subroutine h5file_card

    !> HOLD POSTURE t_r t_d: the start posture held by constant generalized
    !! forces, released at t_r [s] (blank: never) as a step (t_d blank or 0)
    !! or smoothly over t_d [s]; a duration without a release time is
    !! refused. HOLD PRESTRAIN: the start posture settled by pre-straining
    !! the joints' discs and neutral-zone springs (hn_prestrain), nothing
    !! held or released (F2 and F3 blank).
    subroutine hold_card(rd, i, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the HOLD card's image
        type(case_t), intent(inout) :: cs  !! the run case (its times read); out: hold_posture or hold_prestrain, the release
        character(len=10) :: s
        integer :: f
        call rd%name(i, 1, 'option', s)
        if (s /= 'POSTURE' .and. s /= 'PRESTRAIN' .and. .not. rd%failed()) &
            call rd%fail(rd%context(i, 1, 'option')//': found "'//trim(s)//'"; expected POSTURE or PRESTRAIN')
        if (rd%failed()) return
        cs%hold_where = rd%where(i)
        if (s == 'PRESTRAIN') then
            cs%hold_prestrain = .true.
            do f = 2, 3
                if (rd%is_blank(i, f)) cycle
                call rd%fail(rd%context(i, f, 'release')//': found "'//trim(rd%raw(i, f))// &
                             '"; expected blank: a pre-strain stays through the run (HOLD POSTURE is the one released)')
                return
            end do
            return
        end if
        cs%hold_posture = .true.
        if (.not. rd%is_blank(i, 2)) then
            call rd%real(i, 2, 'release time', 's', cs%model%hold_release, cs%t_start, cs%t_end)
            call rd%real(i, 3, 'release duration', 's', cs%model%hold_duration, zero, 1.0e4_wp, default=zero)
            ! a step at the start: the run starts released (its first evaluation is after the step)
            cs%model%hold_stepped = cs%model%hold_duration == zero .and. cs%model%hold_release <= cs%t_start
        else if (.not. rd%is_blank(i, 3)) then
            call rd%fail(rd%context(i, 3, 'release duration')//': found "'//trim(rd%raw(i, 3))// &
                         '" without a release time; expected the release time [s] in F2 (columns 21-30), '// &
                         'or F3 blank (never released)')
        end if
    end subroutine hold_card

    !> The HEADNECK card: the bodies reported as head and T1 (their merged bodies
    !! when MERGE absorbed them); CRITERIA; the LOADCELL and PRINT cards; STATICS.
    subroutine report_cards(rd, cards, cs, bnames, bmap)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(card_t), intent(in) :: cards(:)  !! the deck's cards with their continuation cards (group_cards)
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        character(len=10), intent(in) :: bnames(:)  !! the names of the deck's bodies, in deck order
        type(body_map_t), intent(in) :: bmap  !! where each deck body went (MERGE), what locked its coordinates
        integer :: ic
        cs%head = findloc(bnames, 'HEAD', dim=1)
        if (cs%head == 0) cs%head = size(bnames)
        cs%head = bmap%new(cs%head)
        cs%t1 = findloc(cs%model%tree%parent, 0, dim=1)
        ic = single(cards, 'HEADNECK')
        if (ic > 0) then
            cs%head = bmap%new(body_ref(rd, cards(ic)%first, 1, 'head body', bnames, .false.))
            if (.not. rd%is_blank(cards(ic)%first, 2)) &
                cs%t1 = bmap%new(body_ref(rd, cards(ic)%first, 2, 'T1 body', bnames, .false.))
        end if
        ic = single(cards, 'CRITERIA')
        if (ic > 0) call criteria_card(rd, cards(ic)%first, cs)
        call loadcell_cards(rd, cards, cs, bnames, bmap)
        call print_cards(rd, cards, cs)
        ic = single(cards, 'STATICS')
        if (ic > 0) call statics_card(rd, cards(ic)%first, cs)
    end subroutine report_cards

end module hn_deck_control
