!> Calibration as code: fit named deck parameters (the PARAM cards of the
!! sweep deck: FAMILY scale factors, BODY scales, FIELDn values), within
!! their bounds, to cases of any kind (hn_calibrate_cases) by minimising
!! the objective J (hn_calibrate_objective), the calibration deck read by
!! hn_calibrate_deck; the optimizer's driver and its listing.
!! Optimizer (hn_optimize): a Latin hypercube of starting points (seeded)
!! and Nelder-Mead from the best of them, restarted about its best point
!! while a restart gains more than 1e-4, in the unit cube of the parameter
!! ranges (LOG ranges in logarithms), points clamped to the bounds.
!! Deterministic: the same deck gives the same fit on every machine.
!! Built with OpenMP (fpm.toml), the starting points, and within each
!! evaluation the cases' runs, their analyses at rest and their channels'
!! ISO 18571 ratings, run on every core (OMP_NUM_THREADS); the results are
!! combined in the serial order, so the listing is the same on any number
!! of threads.
module hn_calibrate
    use hn_kinds, only: wp, zero, one, deg
    use hn_sweep, only: sweep_param_t, sweep_design, spread_value, field_text, par_field
    use hn_optimize, only: restarted_nelder_mead
    use hn_rating, only: peak_t, score_t
    use hn_volunteer_data, only: peak_table_t
    use hn_deck_reader, only: int_str
    use hn_joint_limits, only: range_margin
    use hn_calibrate_types, only: calibration_t, reference_case_t, range_score_t, metric_cora, metric_iso18571, standing_case_t
    use hn_calibrate_cases, only: read_calibration
    use hn_calibrate_scores, only: range_score, case_rating
    use hn_calibrate_objective, only: evaluate, member_histories
    implicit none
    private

    public :: calibration_t, reference_case_t, range_score_t, metric_cora, metric_iso18571
    public :: read_calibration, evaluate, calibrate, member_histories, range_score

contains

    !> Run the calibration: the VALUES point (when given) and the LHS starting points, then Nelder-Mead from
    !! the best, restarted about its best point while a restart gains more
    !! than 1e-4 and evaluations are left; the history and the result on
    !! unit lu.
    subroutine calibrate(cal, lu, vbest, jbest, nevals)
        type(calibration_t), intent(in) :: cal   !! the calibration
        integer, intent(in) :: lu                    !! listing unit
        real(wp), intent(out) :: vbest(:)            !! fitted parameter values
        real(wp), intent(out) :: jbest               !! objective there
        integer, intent(out) :: nevals               !! model evaluations (each runs every case)
        real(wp), allocatable :: design(:, :), jdesign(:)
        real(wp) :: u0(size(cal%par)), ubest(size(u0)), j, jstart, lmax, lp, stx(size(cal%stand))
        type(score_t) :: sc(size(cal%sw))
        type(range_score_t) :: rg(size(cal%sw))
        logical :: ok
        integer :: r, k, i, nnm, cu, ios
        logical :: curves_open
        curves_open = .false.
        associate (par => cal%par)
            write (lu, '(a)') 'CALIBRATION: '//trim(cal%title)
            write (lu, '(a,i0,a,i0,a,i0)') 'cases ', size(cal%sw), ', parameters ', size(par), ', seed ', cal%seed
            call optional_report(cal, lu)
            if (cal%range_weight > zero) then
                write (lu, '(a,es10.3,a,es10.3,a,es10.3,a,es10.3,a,es10.3)') 'objective J = (1 - R) + W P + WT T '// &
                    '+ WR G; W ', cal%peak_weight, ', WT ', cal%time_weight, ', WR ', cal%range_weight, &
                    ', PEAK MARGIN M ', cal%peak_margin, ', RANGE MARGIN MR ', cal%range_inside
            else
                write (lu, '(a,es10.3,a,es10.3,a,es10.3)') 'objective J = (1 - R) + W P + WT T; W ', cal%peak_weight, &
                    ', WT ', cal%time_weight, ', PEAK MARGIN M ', cal%peak_margin
            end if
            write (lu, '(a)') 'R: '//trim(merge('MEAN ISO 18571 OVERALL RATING', 'MEAN CORA-STYLE RATING       ', &
                                                cal%metric == metric_iso18571))//' OF THE RATED CHANNELS'
            if (cal%max_evals == 0) then                 ! score the decks as they are, or at VALUES
                vbest = par%nominal
                if (size(cal%values) == size(par)) vbest = cal%values
                if (len_trim(cal%curves) > 0) then
                    open (newunit=cu, file=trim(cal%curves), status='replace', action='write', iostat=ios)
                    if (ios /= 0) then
                        write (lu, '(a)') 'CURVES FILE '//trim(cal%curves)//' CANNOT BE WRITTEN'
                    else
                        write (cu, '(a)') 'case,channel,time_ms,reference,model'
                        curves_open = .true.
                    end if
                end if
                if (curves_open) then
                    call evaluate(cal, vbest, jbest, sc, ok, lmax, lp, curves=cu, ranges=rg, standing=stx)
                    close (cu)
                else
                    call evaluate(cal, vbest, jbest, sc, ok, lmax, lp, ranges=rg, standing=stx)
                end if
                nevals = 1
                call score_report(cal, sc, rg, jbest, lu)
                call rest_report(lmax, lp, stx)
                return
            end if
            design = sweep_design(cal%sw(1))
            if (size(cal%values) == size(par)) design = reshape([cal%values, reshape(design, [size(design)])], &
                                                                [size(par), size(design, 2) + 1])
            jstart = huge(one)
            nevals = 0
            allocate (jdesign(size(design, 2)))
            ! the starting points are independent: on every core (OpenMP), reported in order below
            !$omp parallel do schedule(dynamic, 1) private(sc, ok)
            do r = 1, size(design, 2)
                call evaluate(cal, design(:, r), jdesign(r), sc, ok)
            end do
            !$omp end parallel do
            do r = 1, size(design, 2)
                nevals = nevals + 1
                call report('start', nevals, jdesign(r), design(:, r))
                if (jdesign(r) < jstart) then
                    jstart = jdesign(r)
                    u0 = [(unit_of(par(k), design(k, r)), k=1, size(par))]
                end if
            end do
            call restarted_nelder_mead(obj, u0, 0.15_wp, max(cal%max_evals - nevals, size(par) + 2), 1.0e-4_wp, &
                                       ubest, jbest, nnm)
            vbest = values_of(ubest)
            write (lu, '(a,f9.5,a,i0,a)') 'BEST OBJECTIVE ', jbest, ' AFTER ', nevals, ' EVALUATIONS'
            call evaluate(cal, vbest, j, sc, ok, lmax, lp, ranges=rg, standing=stx)
            call score_report(cal, sc, rg, j, lu)
            call rest_report(lmax, lp, stx)
            do k = 1, size(par)
                write (lu, '(a,a10,a,a10,a,es12.5,a,es12.5,a)') 'PARAM ', par(k)%name, ' = ', field_text(vbest(k)), &
                    '   (bounds ', par(k)%low, ' to ', par(k)%high, ')'
                do i = 1, size(par(k)%ties)
                    associate (t => par(k)%ties(i))
                        write (lu, '(a,a10,a,a10,3x,a10,a10,a,i0)') 'TIE   ', par(k)%name, ' = ', &
                            field_text(t%a + t%b*vbest(k)), t%target, t%item, 'F', t%field
                    end associate
                end do
            end do
        end associate
    contains
        function obj(u) result(f)
            real(wp), intent(in) :: u(:)
            real(wp) :: f
            real(wp) :: v(size(u))
            type(score_t) :: s(size(cal%sw))
            logical :: good
            v = values_of(u)
            call evaluate(cal, v, f, s, good)
            nevals = nevals + 1
            call report('nelder', nevals, f, v)
        end function obj

        function values_of(u) result(v)
            real(wp), intent(in) :: u(:)
            real(wp) :: v(size(u))
            character(len=10) :: txt
            integer :: i
            do i = 1, size(u)
                v(i) = spread_value(cal%par(i), u(i))
                txt = field_text(v(i))
                if (cal%par(i)%kind == par_field) read (txt, *) v(i)
            end do
        end function values_of

        subroutine rest_report(lmax, lp, stx)
            real(wp), intent(in) :: lmax, lp, stx(:)
            integer :: k
            if (lmax > -huge(one)) write (lu, '(a,es10.3,a)') 'LARGEST REAL PART AT REST ', lmax, ' 1/S'// &
                trim(merge(' (NOT JUDGED: THE STANDING CASES ARE)', '                                     ', &
                           size(cal%stand) > 0))
            do k = 1, size(stx)
                if (stx(k) < huge(one)) then
                    write (lu, '(a,i0,a,es10.3,a,es10.3,a)') 'STANDING CASE ', k, ': LARGEST EXCURSION '// &
                        trim(excursion_kind(cal%stand(k)))//' ', &
                        stx(k), ' DEG (BOUND ', cal%stand(k)%bound, ' DEG) '//trim(cal%stand(k)%deck)
                else
                    write (lu, '(a,i0,a)') 'STANDING CASE ', k, ': THE RUN AT REST DID NOT COMPLETE '// &
                        trim(cal%stand(k)%deck)
                end if
            end do
            if (cal%passive .and. lp < huge(one) .and. lp > -huge(one)) &
                write (lu, '(a,es10.3,a)') 'LARGEST REAL PART AT REST WITHOUT MUSCLES ', lp, ' 1/S'
        end subroutine rest_report

        subroutine report(stage, n, f, v)
            character(len=*), intent(in) :: stage
            integer, intent(in) :: n
            real(wp), intent(in) :: f, v(:)
            integer :: i
            write (lu, '(a8,i6,f10.5,*(1x,a10))') stage, n, f, (field_text(v(i)), i=1, size(v))
            flush (lu)
        end subroutine report
    end subroutine calibrate

    !> What a standing case's excursion measures, for the listing: AT REST
    !! (STANDING: the joints), OF THE HEAD (REST: its rotation throughout),
    !! AT THE END (RETURN: the head's rotation where the run ends).
    pure function excursion_kind(sc) result(text)
        type(standing_case_t), intent(in) :: sc   !! the standing case
        character(len=:), allocatable :: text
        select case (sc%kind)
        case ('RETURN'); text = 'AT THE END'
        case ('REST'); text = 'OF THE HEAD'
        case default; text = 'AT REST'
        end select
    end function excursion_kind

    !> Position of value x in the unit range of parameter p (inverse of spread_value).
    pure real(wp) function unit_of(p, x) result(u)
        type(sweep_param_t), intent(in) :: p
        real(wp), intent(in) :: x
        if (p%log_spacing) then
            u = (log(x) - log(p%low))/(log(p%high) - log(p%low))
        else
            u = (x - p%low)/(p%high - p%low)
        end if
        u = min(one, max(zero, u))
    end function unit_of

    !> One listing line per run of consecutive cases that leave out the same
    !! OPTIONAL parameters: 'cases 5-28 without (OPTIONAL, not in their decks): SIGMA ...'.
    subroutine optional_report(cal, lu)
        type(calibration_t), intent(in) :: cal   !! the calibration
        integer, intent(in) :: lu                !! listing unit
        character(len=:), allocatable :: label
        character(len=10), allocatable :: absent(:)
        integer :: k, r, i
        k = 1
        do while (k <= size(cal%sw))
            r = k
            do while (r < size(cal%sw))
                if (any(cal%sw(r + 1)%params%bound .neqv. cal%sw(k)%params%bound)) exit
                r = r + 1
            end do
            if (.not. all(cal%sw(k)%params%bound)) then
                label = trim(int_str(k))
                if (r > k) label = label//'-'//trim(int_str(r))
                absent = pack(cal%sw(k)%params%name, .not. cal%sw(k)%params%bound)
                write (lu, '(a,*(1x,a))') 'cases '//label//' without (OPTIONAL, not in their decks):', &
                    (trim(absent(i)), i=1, size(absent))
            end if
            k = r + 1
        end do
    end subroutine optional_report

    !> The ratings and peaks of every case, three significant digits; each
    !! channel's ISO 18571 scores (overall, corridor, phase, magnitude,
    !! slope) to six digits.
    subroutine score_report(cal, sc, rg, j, lu)
        type(calibration_t), intent(in) :: cal   !! the calibration
        type(score_t), intent(in) :: sc(:)       !! (case) the scores
        type(range_score_t), intent(in) :: rg(:) !! (case) the joints past their ranges
        real(wp), intent(in) :: j                !! the objective
        integer, intent(in) :: lu                !! listing unit
        integer :: c, k
        character(len=10) :: name
        write (lu, '(a,f8.4)') 'OBJECTIVE J = ', j
        do c = 1, size(sc)
            if (.not. (allocated(sc(c)%rating) .and. allocated(sc(c)%iso))) then
                write (lu, '(a,a,a)') 'CASE ', trim(cal%decks(c)), ': NOT RATED (A RUN FAILED, OR THE SET DOES '// &
                    'NOT PASS THE CHECKS AT REST)'
                cycle
            end if
            if (cal%pub(c)%on) then
                write (lu, '(a,a,a,f7.4,a)') 'CASE ', trim(cal%decks(c)), ' (WEIGHT', cal%weight(c), &
                    '): PUBLISHED PEAKS OF '//trim(cal%data(c))//' (NO CURVE RATED)'
                write (lu, '(2x,a,i0,a,f5.1,a,f5.1,a,f8.4)') 'RANGES: ', rg(c)%past, ' JOINT(S) PAST THEIR RANGE BY '// &
                    'MORE THAN ', range_margin/deg, ' DEG; LARGEST EXCESS ', rg(c)%largest/deg, ' DEG; G ', rg(c)%term
                call published_report(cal%pub(c), cal%peaks, sc(c), lu)
                cycle
            end if
            if (any(cal%weight /= one)) then
                write (lu, '(a,a,a,f7.4,a,f7.4)') 'CASE ', trim(cal%decks(c)), ' (WEIGHT', cal%weight(c), &
                    '): MEAN RATING ', case_rating(cal, sc(c))
            else
                write (lu, '(a,a,a,f7.4)') 'CASE ', trim(cal%decks(c)), ': MEAN RATING ', case_rating(cal, sc(c))
            end if
            do k = 1, size(sc(c)%rating)
                if (cal%ref(c)%on) then
                    name = cal%ref(c)%column(k)
                else
                    name = cal%channels(k)%name
                end if
                write (lu, '(2x,a10,a,f6.3,a,f6.3,a,f6.3)') name, ' RATING ', sc(c)%rating(k), &
                    '  C ', sc(c)%corridor(k), '  X ', sc(c)%xcorr(k)
                write (lu, '(2x,a10,a,f9.6,a,f9.6,a,f9.6,a,f9.6,a,f9.6)') name, ' ISO 18571 ', &
                    sc(c)%iso(k)%overall, '  CORRIDOR ', sc(c)%iso(k)%corridor, '  PHASE ', sc(c)%iso(k)%phase, &
                    '  MAGNITUDE ', sc(c)%iso(k)%magnitude, '  SLOPE ', sc(c)%iso(k)%slope
            end do
            write (lu, '(2x,a,i0,a,f5.1,a,f5.1,a,f8.4)') 'RANGES: ', rg(c)%past, ' JOINT(S) PAST THEIR RANGE BY MORE '// &
                'THAN ', range_margin/deg, ' DEG; LARGEST EXCESS ', rg(c)%largest/deg, ' DEG; G ', rg(c)%term
            if (cal%ref(c)%on) cycle
            do k = 1, size(cal%peaks)
                write (lu, '(2x,a16,a,es10.3,a,f6.1,a,es10.3,a,es9.2,a,f6.1,a,f5.1,a,f6.2)') cal%peaks(k)%name, &
                    ' MODEL ', sc(c)%peak(k), ' AT ', sc(c)%time(k), ' MS; VOLUNTEERS ', cal%vol(c)%peak_mean(k), &
                    ' +- ', cal%vol(c)%peak_sd(k), ' AT ', cal%vol(c)%time_mean(k), ' +- ', cal%vol(c)%time_sd(k), &
                    '; Z ', sc(c)%z(k)
            end do
        end do
    end subroutine score_report

    !> The peaks of a case of published peaks that its table gives: the
    !! model's, the published mean and SD (and time), z.
    subroutine published_report(pb, peaks, sc, lu)
        type(peak_table_t), intent(in) :: pb     !! the table
        type(peak_t), intent(in) :: peaks(:)     !! the PEAK cards
        type(score_t), intent(in) :: sc          !! the case's scores
        integer, intent(in) :: lu                !! listing unit
        integer :: k
        do k = 1, size(peaks)
            if (.not. pb%has(k)) cycle
            if (pb%has_time(k)) then
                write (lu, '(2x,a16,a,es10.3,a,f6.1,a,es10.3,a,es9.2,a,f6.1,a,f5.1,a,f6.2)') peaks(k)%name, &
                    ' MODEL ', sc%peak(k), ' AT ', sc%time(k), ' MS; PUBLISHED ', pb%mean(k), ' +- ', pb%sd(k), &
                    ' AT ', pb%time_mean(k), ' +- ', pb%time_sd(k), '; Z ', sc%z(k)
            else
                write (lu, '(2x,a16,a,es10.3,a,f6.1,a,es10.3,a,es9.2,a,f6.2)') peaks(k)%name, ' MODEL ', &
                    sc%peak(k), ' AT ', sc%time(k), ' MS; PUBLISHED ', pb%mean(k), ' +- ', pb%sd(k), '; Z ', sc%z(k)
            end if
        end do
    end subroutine published_report

end module hn_calibrate
