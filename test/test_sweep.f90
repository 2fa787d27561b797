!> Parameter sweeps: the designs (Latin-hypercube strata, factorial
!! combinations, one-at-a-time steps), the sensitivity measures against
!! closed forms, the three kinds of parameter against each other, the
!! sweep deck's located errors, and a sweep with a diverging member that
!! finishes and reports it. The base case is the NBDL deck shortened to
!! 50 ms with RK4 at 50 us, so that each member takes about a second.
program test_sweep
    use hn_kinds, only: wp, zero, one, msglen
    use hn_testing, only: test_suite_t
    use hn_case, only: case_t
    use hn_sweep, only: sweep_t, sweep_param_t, member_record_t, read_sweep, sweep_design, sweep_member_case, &
                        run_member, field_text, par_family, design_lhs, design_factorial, design_oat, nout
    use hn_sweep_report, only: sweep_sensitivities
    use hn_sensitivity, only: oat_sensitivity, regression_sensitivity
    use hn_random, only: rng_t
    use hn_test_models, only: write_lines, delete_file
    use hn_deck, only: read_case
    use hn_run, only: run_state_t, run_result_t
    use hn_channels, only: channel_set_t, channels_define
    implicit none
    type(test_suite_t) :: suite
    character(len=*), parameter :: base = 'test_sweep_base.inp', scratch = 'test_sweep_scratch.inp'

    call write_base()
    call test_lhs_strata()
    call test_lhs_seeded()
    call test_factorial_combinations()
    call test_oat_steps()
    call test_field_text_round_trip()
    call test_oat_elasticity_power_law()
    call test_regression_linear_model()
    call test_regression_needs_enough_runs()
    call test_field_equals_body_scale()
    call test_family_scale_disc_stiffness()
    call test_deck_errors()
    call test_diverging_member()
    call delete_file(base)
    call delete_file(scratch)
    call suite%finish()

contains

    !> The NBDL deck, 50 ms, RK4 at 50 us.
    subroutine write_base()
        character(len=200) :: line
        integer :: u, w, ios
        open (newunit=u, file='input/nbdl15g.inp', status='old', action='read')
        open (newunit=w, file=base, status='replace', action='write')
        do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            if (line(1:8) == 'CONTROL ') line = 'CONTROL   0.05      5.0E-5    0.005     RK4'
            write (w, '(a)') trim(line)
        end do
        ! the disc retardation time of the earlier model (5 ms), so that RK4 at 50 us stays stable
        write (w, '(a)') 'SCALE     RK4STABLE DISCS     VISCOUS   0.2'
        close (u)
        close (w)
    end subroutine write_base

    !> A sweep deck in the scratch file, read.
    subroutine sweep_from(lines, sw, stat, msg)
        character(len=*), intent(in) :: lines(:)
        type(sweep_t), intent(out) :: sw
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: msg
        call write_lines(scratch, lines)
        call read_sweep(scratch, 'sweep', sw, stat, msg)
    end subroutine sweep_from

    !> A sweep of np scale parameters on [lo, hi] without a deck.
    function bare_sweep(design, np, lo, hi, log_spacing) result(sw)
        integer, intent(in) :: design, np
        real(wp), intent(in) :: lo, hi
        logical, intent(in) :: log_spacing
        type(sweep_t) :: sw
        integer :: p
        allocate (sw%params(np))
        do p = 1, np
            sw%params(p)%kind = par_family
            sw%params(p)%low = lo*p
            sw%params(p)%high = hi*p
            sw%params(p)%log_spacing = log_spacing
        end do
        sw%design = design
    end function bare_sweep

    !> LHS: each parameter has exactly one value in each of the n
    !! equal-probability strata (equal widths, in log for LOG spacing).
    subroutine test_lhs_strata()
        type(sweep_t) :: sw
        real(wp), allocatable :: v(:, :), u(:)
        integer :: p, n, spacing
        logical :: ok
        character(len=60) :: what
        n = 37
        ok = .true.
        do spacing = 0, 1
            sw = bare_sweep(design_lhs, 4, 0.5_wp, 2.0_wp, spacing == 1)
            sw%nlhs = n
            sw%seed = 11
            v = sweep_design(sw)
            do p = 1, 4
                associate (q => sw%params(p))
                    if (q%log_spacing) then
                        u = (log(v(p, :)) - log(q%low))/(log(q%high) - log(q%low))
                    else
                        u = (v(p, :) - q%low)/(q%high - q%low)
                    end if
                end associate
                ok = ok .and. all(strata_hit(u, n) == 1)
            end do
        end do
        write (what, '(a,i0,a)') 'n = ', n, ', 4 parameters, LIN and LOG'
        call suite%check(ok .and. size(v, 2) == n, 'Latin hypercube: one value in every stratum of every parameter', &
                         trim(what))
    end subroutine test_lhs_strata

    pure function strata_hit(u, n) result(c)
        real(wp), intent(in) :: u(:)
        integer, intent(in) :: n
        integer :: c(n), k, s
        c = 0
        do k = 1, size(u)
            s = 1 + int(u(k)*n)
            if (s >= 1 .and. s <= n) c(s) = c(s) + 1
        end do
    end function strata_hit

    !> The same seed gives the same design; another seed another design.
    subroutine test_lhs_seeded()
        type(sweep_t) :: sw
        real(wp), allocatable :: a(:, :), b(:, :), c(:, :)
        sw = bare_sweep(design_lhs, 3, 1.0_wp, 2.0_wp, .false.)
        sw%nlhs = 20
        sw%seed = 5
        a = sweep_design(sw)
        b = sweep_design(sw)
        sw%seed = 6
        c = sweep_design(sw)
        call suite%check(all(a == b) .and. any(a /= c), 'Latin hypercube: reproducible from its seed')
    end subroutine test_lhs_seeded

    !> FACTORIAL: levels^np runs, all distinct, ends and middle included.
    subroutine test_factorial_combinations()
        type(sweep_t) :: sw
        real(wp), allocatable :: v(:, :)
        integer :: r, q
        logical :: distinct
        sw = bare_sweep(design_factorial, 3, 1.0_wp, 3.0_wp, .false.)
        sw%levels = 3
        v = sweep_design(sw)
        distinct = .true.
        do r = 1, size(v, 2)
            do q = r + 1, size(v, 2)
                if (all(v(:, r) == v(:, q))) distinct = .false.
            end do
        end do
        call suite%check(size(v, 2) == 27 .and. distinct .and. all(v(1, 1:3) == [1.0_wp, 2.0_wp, 3.0_wp]) .and. &
                         all(v(3, [1, 27]) == [3.0_wp, 9.0_wp]), &
                         'full factorial: 3 levels x 3 parameters = 27 distinct runs spanning each range')
    end subroutine test_factorial_combinations

    !> OAT: run 1 nominal, runs 2p and 2p+1 at -/+ step, the rest nominal.
    subroutine test_oat_steps()
        type(sweep_t) :: sw
        real(wp), allocatable :: v(:, :)
        logical :: ok
        integer :: p
        sw = bare_sweep(design_oat, 3, 1.0_wp, 2.0_wp, .false.)
        sw%percent = 10.0_wp
        sw%params(2)%nominal = 4.0_wp
        v = sweep_design(sw)
        ok = size(v, 2) == 7 .and. all(v(:, 1) == [1.0_wp, 4.0_wp, 1.0_wp])
        do p = 1, 3
            ok = ok .and. abs(v(p, 2*p) - 0.9_wp*sw%params(p)%nominal) < 1.0e-15_wp .and. &
                 abs(v(p, 2*p + 1) - 1.1_wp*sw%params(p)%nominal) < 1.0e-15_wp .and. &
                 count(v(:, 2*p) /= v(:, 1)) == 1 .and. count(v(:, 2*p + 1) /= v(:, 1)) == 1
        end do
        call suite%check(ok, 'one-at-a-time: nominal run, then each parameter alone at -/+ 10 %')
    end subroutine test_oat_steps

    !> A value written into a 10-column field reads back to 6 significant
    !! digits for positive values of 1e-9 to 1e9 (the usual parameters), and
    !! to 4 digits at worst (negative, two-digit exponent: -1.234E-15).
    subroutine test_field_text_round_trip()
        type(rng_t) :: rng
        real(wp) :: x, worst_usual, worst_any
        integer :: k
        worst_usual = zero
        worst_any = zero
        do k = 1, 2000
            x = 10.0_wp**rng%uniform(-9.0_wp, 9.0_wp)
            worst_usual = max(worst_usual, read_back_error(x))
            x = sign(10.0_wp**rng%uniform(-30.0_wp, 30.0_wp), rng%uniform(-1.0_wp, 1.0_wp))
            worst_any = max(worst_any, read_back_error(x))
        end do
        call suite%near(worst_usual, zero, 5.0e-6_wp, 'field text of a swept value in 1e-9..1e9: 6 digits in 10 columns')
        call suite%near(worst_any, zero, 5.0e-4_wp, 'field text of any swept value: 4 digits at worst in 10 columns')
    end subroutine test_field_text_round_trip

    real(wp) function read_back_error(x) result(e)
        real(wp), intent(in) :: x
        character(len=10) :: s
        real(wp) :: y
        integer :: ios
        s = field_text(x)
        read (s, *, iostat=ios) y
        if (ios /= 0) y = huge(one)
        e = abs(y - x)/abs(x)
    end function read_back_error

    !> For y = c x^2 the central-difference elasticity at +-20 % is exactly
    !! [(1.2^2 - 0.8^2)/2]/0.2 = 2; a failed run makes it invalid.
    subroutine test_oat_elasticity_power_law()
        real(wp) :: y(5), s(2)
        logical :: valid(2)
        y = [3.0_wp, 3.0_wp*0.8_wp**2, 3.0_wp*1.2_wp**2, 5.0_wp, 5.0_wp]
        call oat_sensitivity(y, [.true., .true., .true., .true., .false.], 20.0_wp, s, valid)
        call suite%check(abs(s(1) - 2.0_wp) < 1.0e-12_wp .and. valid(1) .and. .not. valid(2), &
                         'OAT elasticity of y = c x^2 is 2; a member that failed leaves it undefined')
    end subroutine test_oat_elasticity_power_law

    !> For y = 3 x1 - 2 x2 + 0 x3 exactly, the standardised regression
    !! coefficients are b_i sd(x_i)/sd(y) and R^2 = 1 (failed runs skipped).
    subroutine test_regression_linear_model()
        type(rng_t) :: rng
        real(wp) :: x(3, 40), y(40), b(3), r2, expect(3), coef(3)
        logical :: ok(40), valid
        integer :: r, p
        coef = [3.0_wp, -2.0_wp, 0.0_wp]
        do r = 1, 40
            do p = 1, 3
                x(p, r) = rng%uniform(0.0_wp, real(p, wp))
            end do
        end do
        y = matmul(coef, x)
        ok = .true.
        ok([7, 19]) = .false.
        y([7, 19]) = 1.0e6_wp            ! junk in failed runs must not matter
        do p = 1, 3
            expect(p) = coef(p)*sd(pack(x(p, :), ok))/sd(pack(y, ok))
        end do
        call regression_sensitivity(x, y, ok, b, r2, valid)
        call suite%check(valid .and. maxval(abs(b - expect)) < 1.0e-10_wp .and. abs(r2 - 1.0_wp) < 1.0e-10_wp, &
                         'standardised regression coefficients of an exact linear model, R^2 = 1')
    end subroutine test_regression_linear_model

    pure real(wp) function sd(a)
        real(wp), intent(in) :: a(:)
        sd = sqrt(sum((a - sum(a)/size(a))**2)/(size(a) - 1))
    end function sd

    subroutine test_regression_needs_enough_runs()
        real(wp) :: x(3, 4), y(4), b(3), r2
        logical :: valid
        x = 1.0_wp
        x(1, :) = [1.0_wp, 2.0_wp, 3.0_wp, 4.0_wp]
        y = [1.0_wp, 2.0_wp, 3.0_wp, 5.0_wp]
        call regression_sensitivity(x, y, [.true., .true., .true., .true.], b, r2, valid)
        call suite%check(.not. valid .and. all(b == zero), 'regression refused with fewer runs than parameters + 2')
    end subroutine test_regression_needs_enough_runs

    !> Two routes to the same head mass: FIELD3 of the HEAD body card
    !! (value written into the deck) and BODY HEAD MASS (scale factor).
    subroutine test_field_equals_body_scale()
        type(sweep_t) :: a, b
        type(case_t) :: ca, cb
        integer :: sa, sb, k
        character(len=msglen) :: ma, mb
        call sweep_from([character(len=80) :: 'TITLE     FIELD', 'BASE      '//base, 'DESIGN    OAT       20.0', &
                         'PARAM     M         FIELD3    BODY      HEAD'], a, sa, ma)
        call sweep_from([character(len=80) :: 'TITLE     SCALE', 'BASE      '//base, 'DESIGN    OAT       20.0', &
                         'PARAM     M         BODY      HEAD      MASS'], b, sb, mb)
        if (sa /= 0 .or. sb /= 0) then
            call suite%check(.false., 'head mass by FIELD3 equals head mass by BODY scale', trim(ma)//trim(mb))
            return
        end if
        call sweep_member_case(a, [1.2_wp*a%params(1)%nominal], ca, sa, ma)
        call sweep_member_case(b, [1.2_wp], cb, sb, mb)
        k = cb%model%tree%nbody
        call suite%check(sa == 0 .and. sb == 0 .and. abs(a%params(1)%nominal - 3.847_wp) < 1.0e-12_wp .and. &
                         abs(ca%model%tree%mass(k) - cb%model%tree%mass(k)) < 1.0e-12_wp .and. &
                         abs(cb%model%tree%mass(k) - 1.2_wp*3.847_wp) < 1.0e-12_wp, &
                         'head mass by FIELD3 (deck text) equals head mass by BODY HEAD MASS (scale 1.2)')
    end subroutine test_field_equals_body_scale

    !> DISCS E x 1.5: every disc's axial stiffness EA/h (closed form) and
    !! the whole stiffness matrix scale by 1.5 when G scales with it.
    subroutine test_family_scale_disc_stiffness()
        type(sweep_t) :: sw
        type(case_t) :: c0, c1
        integer :: stat, e
        character(len=msglen) :: msg
        real(wp) :: worst
        call sweep_from([character(len=80) :: 'TITLE     DISCS', 'BASE      '//base, 'DESIGN    OAT       20.0', &
                         'PARAM     E         FAMILY    DISCS     E', 'PARAM     G         FAMILY    DISCS     G'], &
                        sw, stat, msg)
        call sweep_member_case(sw, [one, one], c0, stat, msg)
        call sweep_member_case(sw, [1.5_wp, 1.5_wp], c1, stat, msg)
        worst = zero
        do e = 1, size(c1%model%discs)
            associate (d => c1%model%discs(e))
                worst = max(worst, abs(d%k(3, 3) - d%d1*d%area/d%h)/(d%d1*d%area/d%h))
                worst = max(worst, maxval(abs(d%k - 1.5_wp*c0%model%discs(e)%k))/maxval(abs(d%k)))
            end associate
        end do
        call suite%check(stat == 0 .and. worst < 1.0e-12_wp .and. size(c1%model%discs) == 8, &
                         'DISCS E and G x 1.5: axial stiffness = E A/h, stiffness matrices x 1.5', trim(msg))
    end subroutine test_family_scale_disc_stiffness

    !> Bad sweep decks: refused with the line and columns (or parameter).
    subroutine test_deck_errors()
        type(sweep_t) :: sw
        integer :: stat
        character(len=msglen) :: msg
        logical :: ok
        ok = .true.
        call sweep_from([character(len=80) :: 'TITLE     X', 'BASE      '//base, 'DESIGN    SOBOL     20.0', &
                         'PARAM     E         FAMILY    DISCS     E'], sw, stat, msg)
        ok = ok .and. stat /= 0 .and. index(msg, 'sweep line 3, columns 11-20') > 0 .and. index(msg, 'OAT') > 0
        call sweep_from([character(len=80) :: 'TITLE     X', 'BASE      '//base, 'DESIGN    OAT       20.0', &
                         'PARAM     E         FAMILY    DISCS     STIFF'], sw, stat, msg)
        ok = ok .and. stat /= 0 .and. index(msg, 'sweep line 4, columns 41-50') > 0
        call sweep_from([character(len=80) :: 'TITLE     X', 'BASE      '//base, 'DESIGN    OAT       20.0', &
                         'PARAM     E         FIELD3    BODY      NECK'], sw, stat, msg)
        ok = ok .and. stat /= 0 .and. index(msg, 'sweep line 4') > 0 .and. index(msg, 'found 0 BODY cards named NECK') > 0
        call sweep_from([character(len=80) :: 'TITLE     X', 'BASE      '//base, 'DESIGN    LHS       10        3', &
                         'PARAM     M         FIELD3    BODY      HEAD      -1.0      4.0'], sw, stat, msg)
        ok = ok .and. stat /= 0 .and. index(msg, 'refused by the base deck') > 0 .and. &
             index(msg, 'columns 31-40') > 0
        call sweep_from([character(len=80) :: 'TITLE     X', 'BASE      missing_base.inp', 'DESIGN    OAT       20.0', &
                         'PARAM     E         FAMILY    DISCS     E'], sw, stat, msg)
        ok = ok .and. stat /= 0 .and. index(msg, 'sweep line 2') > 0 .and. index(msg, 'missing_base.inp') > 0
        call sweep_from([character(len=80) :: 'TITLE     X', 'BASE      '//base, 'DESIGN    LHS       10        3', &
                         'PARAM     E         FAMILY    DISCS     E         2.0       1.0'], sw, stat, msg)
        ok = ok .and. stat /= 0 .and. index(msg, 'sweep line 4, columns 61-70') > 0
        call suite%check(ok, 'bad sweep decks refused with line and columns: design, item, card, value, base, range', &
                         trim(msg))
    end subroutine test_deck_errors

    !> A 2-level factorial on disc stiffness x1 and x1000: the stiff member
    !! is beyond RK4's stability limit. The sweep finishes; the failure is
    !! recorded with its exit code and message, its outputs are zero (no
    !! NaN) and the complete member's outputs are real numbers.
    subroutine test_diverging_member()
        type(sweep_t) :: sw
        type(member_record_t) :: recs(2)
        real(wp), allocatable :: v(:, :)
        real(wp) :: s(1, nout), r2(nout)
        logical :: valid(1, nout)
        integer :: stat, r
        character(len=msglen) :: msg
        call sweep_from([character(len=80) :: 'TITLE     DIVERGING MEMBER', 'BASE      '//base, &
                         'DESIGN    FACTORIAL 2', 'PARAM     DISC_E    FAMILY    DISCS     E         1.0       1000.0'], &
                        sw, stat, msg)
        if (stat /= 0) then
            call suite%check(.false., 'a sweep with a diverging member finishes and records it', trim(msg))
            return
        end if
        v = sweep_design(sw)
        do r = 1, size(v, 2)
            call run_member(sw, v(:, r), recs(r))
        end do
        call sweep_sensitivities(sw, v, recs, s, valid, r2)
        call suite%check(recs(1)%status == 0 .and. recs(2)%status == 3 .and. &
                         index(recs(2)%message, 'stability limit') > 0 .and. all(recs(2)%outputs == zero) .and. &
                         all(abs(recs(1)%outputs) < huge(one)) .and. recs(1)%outputs(12) > zero .and. &
                         .not. any(valid), &
                         'a sweep with a diverging member finishes and records its exit code and message', &
                         trim(recs(2)%message))
        call suite%check(abs(recs(1)%t_reached - 0.05_wp) < 1.0e-9_wp .and. recs(2)%t_reached < 0.05_wp, &
                         'the complete member reaches the end time, the diverging one stops early')
        call check_against_direct_run(recs(1))
    end subroutine test_diverging_member

    !> The member at scale 1 is the base deck: its peak head rotation and
    !! time equal those of the base deck read from its file and run directly.
    subroutine check_against_direct_run(rec)
        type(member_record_t), intent(in) :: rec
        type(case_t) :: cs
        type(run_result_t) :: res
        type(channel_set_t) :: ch
        integer :: stat, lu, k, i
        character(len=msglen) :: msg
        real(wp) :: peak, t_peak
        call read_case(base, base, cs, stat, msg)
        open (newunit=lu, file='/dev/null', action='write')
        block
            type(run_state_t) :: run
            call run%execute(cs, lu, '', res, keep_samples=.true.)
        end block
        close (lu)
        call channels_define(cs, ch)
        k = findloc(ch%name, 'HEAD_THETY', dim=1)
        i = maxloc(abs(res%samples(k, :)), dim=1)
        peak = res%samples(k, i)
        t_peak = 1000.0_wp*res%samples_t(i)
        call suite%check(stat == 0 .and. res%exit_code == 0 .and. abs(rec%outputs(1) - peak) <= 1.0e-12_wp*abs(peak) &
                         .and. abs(rec%outputs(2) - t_peak) <= 1.0e-9_wp, &
                         'the member at scale 1 equals the base deck run directly (peak head rotation and time)')
    end subroutine check_against_direct_run

end program test_sweep
