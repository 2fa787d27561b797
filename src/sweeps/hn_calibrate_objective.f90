!> The objective of a calibration (hn_calibrate), fitting named deck
!! parameters within their bounds to cases of any kind -- volunteers (DATA
!! a directory of their runs), a reference (DATA a reference CSV: a
!! specimen corridor's midline, a segment test's mean) or published peaks
!! (DATA a CSV whose header is peak,mean,sd[,time_mean,time_sd]: a
!! severity whose paper gives the volunteers' peaks alone): the weighted
!! mean over the cases (CASE F7, default 1) of
!!
!!   J_c = (1 - R_c) + w P_c + wt T_c,
!!
!! R_c the case's mean rating of its rated channels by the RATING card's
!! metric (F5): CORA (the default) the CORA-style rating (hn_rating),
!! ISO18571 the overall ISO/TS 18571 rating (hn_iso18571, the formulas of
!! objective-rating-metrics) against the volunteers' mean curve on the
!! RATING window, or the reference curve on the rows it is given. A
!! volunteer case rates the deck's CHANNEL cards (CFC filtered, as the
!! volunteers' runs), a reference case the columns of its CSV as its
!! RATED cards map them to model channels (unfiltered: the reference is
!! as digitised). P_c the mean over the case's peaks
!! (PEAK cards) of max(0, |z| - (1 - m)), z the peak's distance from the
!! volunteers' mean in SDs and m a margin inside the 1 SD band, T the mean
!! over the same peaks of max(0, |dt|/tol - (1 - m)), dt the peak time's
!! distance from the volunteers' mean time and tol the peak-time tolerance
!! of the RATING card (the same margin keeps the times off its edge;
!! a reference case has no peaks: P_c = T_c = 0; a case of published
!! peaks has no rated curve, R_c = 1, and its P_c and T_c are over the
!! peaks its table gives, against the table's means and SDs); w
!! (default 0.02), wt (default 0) and m (default 0) are fields 5, 6 and 7
!! of the FIT card; subject to the model standing at rest: a parameter set
!! whose start state (posture held, the bracing activation) has an
!! eigenvalue with real part above -1 1/s in any case (hn_rest_modes) is
!! not run and gets J = 2 + 0.1 s (lmax + 1) (volunteer cases only: a
!! reference case is held as its deck holds it; with STANDING cards, a set
!! that moves a joint of a standing deck's run at rest more than its bound
!! instead, J = 2 + 0.1 (r - 1), r the largest ratio of excursion to
!! bound); with a PASSIVE card, nor is a
!! set whose neck stands without its muscles (largest real part at rest,
!! muscles off, below the card's limit, default 0: the osteoligamentous
!! column buckles under far less than the head's weight), which gets
!! J = 2 + 0.1 s (limit - lp). With a RANGES card of weight wr, J_c gains
!! wr G_c, G_c the sum over the joints' ranges (ROM cards) of
!! max(0, e_k/e_m - (1 - mr)), e_k the joint's largest excess beyond its
!! physiological range in the run, e_m the margin past which a run warns
!! (hn_joint_limits range_margin, 5 deg) and mr a margin kept inside it
!! (RANGES F2, default 0): a fit kept inside the ranges the runs are
!! checked against. The study itself (the volunteer files, the
!! channels they are compared with, the rating window, the filter, the
!! peaks and their windows) is the deck's RATING, CHANNEL and PEAK cards;
!! nothing of it is compiled in.
!! Member runs are those of the sweep (sweep_member_case, run_state_t):
!! no result file, the listing to /dev/null; a volunteer case sampled at
!! 0.1 ms or finer (its CFC filter), a reference case at its deck's OUTPUT
!! interval (the curves its result file would hold: a segment test's 10 ms).
module hn_calibrate_objective
    use hn_kinds, only: wp, zero, one, msglen
    use hn_status, only: stat_ok
    use hn_case, only: case_t
    use hn_sweep, only: sweep_member_case
    use hn_run, only: run_state_t, run_result_t, exit_ok
    use hn_channels, only: channel_set_t, channels_define, chname_len
    use hn_rating, only: score_t, score_curves
    use hn_prestrain, only: prestrain_t, settle_prestrain
    use hn_rest_modes, only: rest_mode_t, rest_modes
    use hn_model, only: model_t
    use hn_calibrate_types, only: calibration_t, range_score_t
    use hn_calibrate_scores, only: add_peak_terms, range_score, case_rating, score_iso_volunteers, &
                                   score_reference, score_published, rated_histories
    implicit none
    private

    public :: evaluate, member_histories

    real(wp), parameter :: failed_objective = 10.0_wp        !! J of a parameter set whose run fails
    real(wp), parameter :: rest_margin = -1.0_wp             !! largest real part allowed at rest [1/s]
    real(wp), parameter :: unstable_objective = 2.0_wp       !! J of a set unstable at rest, at the margin
    real(wp), parameter :: unstable_slope = 0.1_wp           !! its growth per 1/s beyond the margin [s]

contains

    !> Objective J and the scores of every case for parameter values v. A
    !! parameter set whose model is not stable at rest with the margin
    !! (largest real part above rest_margin in any case: a braced neck
    !! stands) is not run: J = 2 + 0.1 s (lmax - rest_margin), worse than
    !! any stable set whose w P + wt T stays below 1, and decreasing
    !! towards stability. With STANDING cards their runs judge standing
    !! instead: a set that moves a joint of a standing case more than its
    !! bound (the largest ratio r of excursion to bound above 1) is not
    !! run, J = 2 + 0.1 (r - 1). With a PASSIVE card, nor is a set whose neck
    !! stands without its muscles (largest real part at rest below the
    !! card's limit): J = 2 + 0.1 s (limit - lp). Otherwise J is the
    !! weighted mean of the cases' J_c (the module's description); every
    !! case's channels are rated by both metrics (sc: CORA-style in
    !! rating, corridor, xcorr; ISO 18571 in iso), the RATING card's
    !! metric enters J. With `curves`, the rated curves (the samples each
    !! rating is given: reference and model) are written to that unit as
    !! CSV rows case,channel,time_ms,reference,model.
    subroutine evaluate(cal, v, j, sc, ok, growth, passive_growth, curves, ranges, standing)
        type(calibration_t), intent(in) :: cal       !! the calibration
        real(wp), intent(in) :: v(:)                 !! one value per parameter
        real(wp), intent(out) :: j                   !! the objective
        type(score_t), intent(out) :: sc(:)          !! (ncase) ratings and peaks of each case
        logical, intent(out) :: ok                   !! every run complete
        real(wp), intent(out), optional :: growth    !! largest real part at rest over the cases [1/s]
        real(wp), intent(out), optional :: passive_growth !! the same without the muscles (PASSIVE card) [1/s]
        integer, intent(in), optional :: curves      !! unit of the rated curves' CSV (written when present)
        type(range_score_t), intent(out), optional :: ranges(:) !! (ncase) the joints past their ranges in each run
        real(wp), intent(out), optional :: standing(:)   !! (STANDING cards) each case's largest excursion at rest [deg]
        real(wp), allocatable :: y(:, :)
        real(wp) :: rsum, psum, tsum, gsum, wsum, lmax, lp, r, exc(size(cal%stand))
        type(range_score_t) :: rg
        integer :: c, k
        type(case_t), allocatable :: css(:)
        type(run_result_t), allocatable :: ress(:)
        type(channel_set_t), allocatable :: chs(:)
        logical :: oks(size(cal%sw))
        call rest_growth(cal, v, lmax, lp)
        if (present(growth)) growth = lmax
        if (present(passive_growth)) passive_growth = huge(one)
        if (size(cal%stand) > 0) then
            exc = standing_excursions(cal, v)
            if (present(standing)) standing = exc
            r = maxval(exc/cal%stand%bound)
            if (r > one) then
                ok = .false.
                j = rest_penalty(r - one)
                return
            end if
        else if (lmax > rest_margin) then
            ok = .false.
            j = rest_penalty(lmax - rest_margin)
            return
        end if
        if (cal%passive) then
            if (present(passive_growth)) passive_growth = lp
            if (lp < cal%passive_limit) then
                ok = .false.
                j = rest_penalty(cal%passive_limit - lp)
                return
            end if
        end if
        j = failed_objective
        rsum = zero; psum = zero; tsum = zero; gsum = zero; wsum = zero
        allocate (css(size(cal%sw)), chs(size(cal%sw)), ress(size(cal%sw)))
        ! the member runs are independent: on every core (OpenMP), scored in order below
        !$omp parallel do schedule(dynamic, 1) if (size(cal%sw) > 1)
        do c = 1, size(cal%sw)
            call run_member(cal, c, v, css(c), chs(c), ress(c), oks(c))
        end do
        !$omp end parallel do
        do c = 1, size(cal%sw)
            ok = oks(c)
            if (.not. ok) return
            associate (cs => css(c), ch => chs(c), res => ress(c))
                rg = range_score(res%range_peak, cal%range_inside)
                if (present(ranges)) ranges(c) = rg
                gsum = gsum + cal%weight(c)*rg%term
                if (cal%ref(c)%on) then
                    call score_reference(cal%ref(c), ch%name, cs%t_start, cs%sample_dt, res%samples, sc(c), c, curves)
                else if (cal%pub(c)%on) then
                    call score_published(cal, c, ch%name, cs%t_start, cs%sample_dt, res%samples, sc(c))
                    call add_peak_terms(cal, c, sc(c), cal%pub(c)%time_mean, cal%pub(c)%has, cal%pub(c)%has_time, &
                                        psum, tsum)
                else
                    allocate (y(size(cal%vol(c)%t), size(cal%channels)))
                    y = rated_histories(cal, cal%vol(c)%t, ch%name, cs%t_start, cs%sample_dt, res%samples)
                    call score_curves(cal%vol(c), y, cal%window, cal%peaks, sc(c))
                    call score_iso_volunteers(cal, c, y, sc(c), curves)
                    deallocate (y)
                    call add_peak_terms(cal, c, sc(c), cal%vol(c)%time_mean, [(.true., k=1, size(cal%peaks))], &
                                        [(.true., k=1, size(cal%peaks))], psum, tsum)
                end if
            end associate
            rsum = rsum + cal%weight(c)*case_rating(cal, sc(c))
            wsum = wsum + cal%weight(c)
        end do
        j = (one - rsum/wsum) + (cal%peak_weight*psum + cal%time_weight*tsum + cal%range_weight*gsum)/wsum
    end subroutine evaluate

    !> Largest real part of the eigenvalues at rest (hn_rest_modes: the
    !! start state of every volunteer case, posture held as the case holds
    !! it; a living subject's braced neck stands) over the volunteer cases
    !! at parameter values v [1/s] (-huge without one), with the muscles (lmax) and,
    !! for a PASSIVE card, without them (lp; huge without the card). Huge
    !! when a case cannot be built or analysed. The analyses run on every
    !! core (OpenMP) and are combined in the cases' order.
    subroutine rest_growth(cal, v, lmax, lp)
        type(calibration_t), intent(in) :: cal       !! the calibration
        real(wp), intent(in) :: v(:)                 !! one value per parameter
        real(wp), intent(out) :: lmax                !! with the muscles [1/s]
        real(wp), intent(out) :: lp                  !! without them [1/s]
        real(wp) :: growth(2, size(cal%sw))
        logical :: done(2, size(cal%sw))
        integer :: c, t
        ! every analysis on its own core (OpenMP): each case with (1) and without (2) its muscles
        done = .false.
        !$omp parallel do schedule(dynamic, 1)
        do t = 1, 2*size(cal%sw)
            if (cal%ref((t + 1)/2)%on) cycle            ! a reference case is held as its deck holds it
            if (mod(t, 2) == 0 .and. .not. cal%passive) cycle
            call case_growth(cal, (t + 1)/2, v, mod(t, 2) == 0, growth(2 - mod(t, 2), (t + 1)/2), &
                             done(2 - mod(t, 2), (t + 1)/2))
        end do
        !$omp end parallel do
        lmax = -huge(one)
        lp = merge(-huge(one), huge(one), cal%passive)
        do c = 1, size(cal%sw)                          ! in order, as one core would
            if (cal%ref(c)%on) cycle
            if (.not. done(1, c)) then
                lmax = huge(one); return
            end if
            lmax = max(lmax, growth(1, c))
            if (.not. cal%passive) cycle
            if (.not. done(2, c)) then
                lp = huge(one)
            else if (lp < huge(one)) then
                lp = max(lp, growth(2, c))
            end if
        end do
    end subroutine rest_growth

    !> The largest real part at rest of case c at parameter values v [1/s]
    !! (-huge without a mode), with its muscles or without them (passive);
    !! done false when the case cannot be built or analysed.
    subroutine case_growth(cal, c, v, passive, growth, done)
        type(calibration_t), intent(in) :: cal       !! the calibration
        integer, intent(in) :: c                     !! the case
        real(wp), intent(in) :: v(:)                 !! one value per parameter
        logical, intent(in) :: passive               !! its active muscles switched off
        real(wp), intent(out) :: growth              !! the largest real part [1/s]
        logical, intent(out) :: done                 !! the analysis was made
        type(case_t) :: cs
        type(rest_mode_t), allocatable :: modes(:)
        integer :: stat, f
        character(len=msglen) :: msg
        growth = -huge(one)
        call sweep_member_case(cal%sw(c), v, cs, stat, msg)
        if (stat == stat_ok .and. passive) then
            do f = 1, size(cs%model%family)
                if (cs%model%family(f)%f%active_muscle()) cs%model%family_on(f) = .false.
            end do
        end if
        if (stat == stat_ok) call case_rest_modes(cs, modes, stat, msg)
        done = stat == stat_ok
        if (done .and. size(modes) > 0) growth = modes(1)%re
    end subroutine case_growth

    !> The largest excursion of any joint rotation from its start [deg] in
    !! the run of each STANDING deck at parameter values v (RETURN: the
    !! change of the head's rotation vector relative to R at the run's end;
    !! REST: its largest change over the run) (its joint or head rotation
    !! channels alone, at the deck's OUTPUT interval); a run that cannot be
    !! built or does not complete counts as fallen (huge).
    function standing_excursions(cal, v) result(exc)
        type(calibration_t), intent(in) :: cal       !! the calibration
        real(wp), intent(in) :: v(:)                 !! one value per parameter
        real(wp) :: exc(size(cal%stand))
        type(case_t) :: cs
        type(channel_set_t) :: chs
        type(run_result_t) :: res
        character(len=chname_len), allocatable :: joints(:)
        character(len=msglen) :: msg
        integer :: k, stat, lu, n
        exc = huge(one)
        !$omp parallel do schedule(dynamic, 1) private(cs, chs, res, joints, msg, stat, lu, n)
        do k = 1, size(cal%stand)
            call sweep_member_case(cal%stand(k)%sw, v, cs, stat, msg, deck_sampling=.true.)
            if (stat /= stat_ok) cycle
            call channels_define(cs, chs)
            if (cal%stand(k)%kind /= 'STANDING') then   ! RETURN, REST: the head's rotation vector relative to R
                joints = [character(len=chname_len) :: 'HEADL_VX', 'HEADL_VY', 'HEADL_VZ']
            else
                joints = pack(chs%name, chs%group(:)(1:6) == 'JOINTS')
            end if
            if (size(joints) == 0) cycle
            open (newunit=lu, file='/dev/null', action='write')
            block
                type(run_state_t) :: run
                call run%execute(cs, lu, '', res, keep_samples=.true., only=joints)
            end block
            close (lu)
            if (res%exit_code /= exit_ok) cycle
            n = size(res%samples, 2)
            select case (cal%stand(k)%kind)
            case ('STANDING')   ! the largest excursion of any joint rotation
                exc(k) = maxval(abs(res%samples(:, 1:n) - spread(res%samples(:, 1), 2, n)))
            case ('RETURN')     ! the head's change where the run ends
                exc(k) = norm2(res%samples(:, n) - res%samples(:, 1))
            case default        ! REST: the head's largest change over the run
                exc(k) = sqrt(maxval(sum((res%samples(:, 1:n) - spread(res%samples(:, 1), 2, n))**2, dim=1)))
            end select
        end do
        !$omp end parallel do
    end function standing_excursions

    !> The rest modes of a case at its start, held or settled as its run
    !! starts (HOLD POSTURE's forces, or HOLD PRESTRAIN's pre-strain of a
    !! copy of its model).
    subroutine case_rest_modes(cs, modes, stat, msg)
        type(case_t), intent(in) :: cs                          !! the case
        type(rest_mode_t), allocatable, intent(out) :: modes(:) !! its rest modes (rest_modes)
        integer, intent(out) :: stat                            !! stat_ok, or what failed
        character(len=msglen), intent(out) :: msg               !! what failed
        type(model_t) :: settled
        type(prestrain_t) :: ps
        if (.not. cs%hold_prestrain) then
            call rest_modes(cs%model, cs%t_start, cs%x0, cs%xd0, cs%hold_posture, modes, stat, msg)
            return
        end if
        settled = cs%model
        call settle_prestrain(settled, cs%t_start, cs%x0, cs%xd0, ps, stat, msg)
        if (stat == stat_ok) call rest_modes(settled, cs%t_start, cs%x0, cs%xd0, .false., modes, stat, msg)
    end subroutine case_rest_modes

    !> J of a parameter set that fails a check at rest by `excess` [1/s]:
    !! 2 + 0.1 s excess, worse than any set that passes, and decreasing
    !! towards the check's limit.
    pure real(wp) function rest_penalty(excess) result(j)
        real(wp), intent(in) :: excess
        j = min(failed_objective, unstable_objective + unstable_slope*excess)
    end function rest_penalty

    !> Run every volunteer case of the calibration at parameter values v:
    !! the rated channels at the volunteers' times, y(:, :, case) (zero for
    !! a reference case); ok false when a run fails.
    subroutine member_histories(cal, v, y, ok)
        type(calibration_t), intent(in) :: cal   !! the calibration
        real(wp), intent(in) :: v(:)                 !! one value per parameter
        real(wp), intent(out) :: y(:, :, :)          !! (nt, nchannel, ncase)
        logical, intent(out) :: ok               !! every run complete
        type(case_t) :: cs
        type(run_result_t) :: res
        type(channel_set_t) :: ch
        integer :: c
        ok = .true.
        y = zero
        do c = 1, size(cal%sw)
            if (cal%ref(c)%on .or. cal%pub(c)%on) cycle
            call run_member(cal, c, v, cs, ch, res, ok)
            if (.not. ok) return
            y(1:size(cal%vol(c)%t), :, c) = rated_histories(cal, cal%vol(c)%t, ch%name, cs%t_start, cs%sample_dt, &
                                                             res%samples)
        end do
    end subroutine member_histories

    !> Run case c at parameter values v as a sweep member: no result file,
    !! the listing to /dev/null (its header only: no tables, peaks or
    !! criteria), only the rated channels computed, their samples kept in res.
    subroutine run_member(cal, c, v, cs, ch, res, ok)
        type(calibration_t), intent(in) :: cal   !! the calibration
        integer, intent(in) :: c                 !! the case
        real(wp), intent(in) :: v(:)             !! one value per parameter
        type(case_t), intent(out) :: cs          !! the member's case
        type(channel_set_t), intent(out) :: ch   !! its channels
        type(run_result_t), intent(out) :: res   !! its run, with the samples
        logical, intent(out) :: ok               !! the run is complete
        integer :: stat, lu
        character(len=msglen) :: msg
        character(len=chname_len), allocatable :: rated(:)
        ok = .false.
        call sweep_member_case(cal%sw(c), v, cs, stat, msg, deck_sampling=cal%ref(c)%on)
        if (stat /= stat_ok) return
        ! the rated channels alone: the CHANNEL cards' or the RATED cards' (and what they subtract)
        if (cal%ref(c)%on) then
            rated = [character(len=chname_len) :: cal%ref(c)%channel, &
                     pack(cal%ref(c)%minus, len_trim(cal%ref(c)%minus) > 0)]
        else
            rated = [character(len=chname_len) :: cal%channels%name]
        end if
        open (newunit=lu, file='/dev/null', action='write')
        block
            type(run_state_t) :: run         ! a fresh run object for every case
            call run%execute(cs, lu, '', res, keep_samples=.true., only=rated)
        end block
        close (lu)
        if (res%exit_code /= exit_ok) return
        call channels_define(cs, ch, rated)
        ok = .true.
    end subroutine run_member

end module hn_calibrate_objective
