!> The scores of a calibration's member runs (hn_calibrate_objective): a
!! run's rated channels filtered and resampled to the data's times, rated
!! against the volunteers' mean (CORA-style and ISO/TS 18571 on the
!! RATING window), a reference curve on the rows it is given, or the
!! published peaks; the peak terms P_c and T_c, the ranges' term G_c and
!! a case's mean rating R_c by the RATING card's metric; the rated curves
!! as CSV rows.
module hn_calibrate_scores
    use hn_kinds, only: wp, zero, one, msglen
    use hn_filters, only: cfc_filter
    use hn_tables, only: resample
    use hn_rating, only: score_t, cora_rating, curve_peak
    use hn_iso18571, only: iso18571_rating, iso18571_dt
    use hn_joint_limits, only: range_margin
    use hn_calibrate_types, only: calibration_t, reference_case_t, range_score_t, metric_iso18571
    implicit none
    private

    public :: add_peak_terms, range_score, case_rating, window_rows, rated_interval, score_iso_volunteers, &
              score_reference, score_published, rated_histories

contains

    !> Add case c's peak terms, weighted, to the sums of P and T: the mean
    !! over the peaks it has of max(0, |z| - (1 - m)), and of max(0, |t -
    !! t_mean|/tol - (1 - m)) over those of them with a time.
    pure subroutine add_peak_terms(cal, c, sc, time_mean, has, has_time, psum, tsum)
        type(calibration_t), intent(in) :: cal   !! the calibration (weights, margin, tolerance)
        integer, intent(in) :: c                 !! the case
        type(score_t), intent(in) :: sc          !! its scores (z and times of every peak)
        real(wp), intent(in) :: time_mean(:)     !! (peak) the volunteers' mean time [ms]
        logical, intent(in) :: has(:)            !! (peak) the case has the peak
        logical, intent(in) :: has_time(:)       !! (peak) and its time
        real(wp), intent(inout) :: psum          !! sum of the weighted P_c
        real(wp), intent(inout) :: tsum          !! sum of the weighted T_c
        psum = psum + cal%weight(c)*sum(max(zero, abs(sc%z) - (one - cal%peak_margin)), mask=has)/count(has)
        tsum = tsum + cal%weight(c)*sum(max(zero, abs(sc%time - time_mean)/cal%time_tolerance - &
                                            (one - cal%peak_margin)), mask=has_time)/count(has)
    end subroutine add_peak_terms

    !> The joints of a run past their physiological ranges: G, the sum over
    !! the ranges of max(0, e_k/e_m - (1 - m)) (e_k the largest excess of
    !! range k, e_m = range_margin, m the margin kept inside it), the number past
    !! the margin (those a run warns of) and the largest excess.
    pure function range_score(peak, m) result(rg)
        real(wp), intent(in) :: peak(:)          !! (range) largest excess beyond each range [rad]
        real(wp), intent(in) :: m                !! margin kept inside e_m, as a fraction of it
        type(range_score_t) :: rg
        rg%term = sum(max(zero, peak/range_margin - (one - m)))
        rg%past = count(peak > range_margin)
        rg%largest = maxval([zero, peak])
    end function range_score

    !> The mean rating of a case's channels by the calibration's metric.
    pure real(wp) function case_rating(cal, sc) result(r)
        type(calibration_t), intent(in) :: cal   !! the calibration (its metric)
        type(score_t), intent(in) :: sc          !! the case's scores
        if (size(sc%rating) == 0) then          ! published peaks: no curve to rate, J_c = w P_c + wt T_c
            r = one
        else if (cal%metric == metric_iso18571) then
            r = sum(sc%iso%overall)/size(sc%iso)
        else
            r = sum(sc%rating)/size(sc%rating)
        end if
    end function case_rating

    !> The first and last of the evenly spaced times t within the window.
    pure subroutine window_rows(t, window, i1, i2)
        real(wp), intent(in) :: t(:)             !! times [ms]
        real(wp), intent(in) :: window(2)        !! first and last time [ms]
        integer, intent(out) :: i1               !! the first row
        integer, intent(out) :: i2               !! the last row (i2 < i1: none)
        i1 = findloc(t >= window(1) .and. t <= window(2), .true., dim=1)
        i2 = findloc(t >= window(1) .and. t <= window(2), .true., dim=1, back=.true.)
    end subroutine window_rows

    !> The sampling interval ISO 18571 takes the rows of rated channel m
    !! of a reference case at [s]: its CSV's time step, or with SAMPLES
    !! (RATED F6) the rating's own 0.1 ms (each row one sample: a curve
    !! whose abscissa is not time, as a moment-rotation curve read on a
    !! moment ramp, is rated as the catalogue rates it, not resampled).
    pure real(wp) function rated_interval(rf, m) result(dt)
        type(reference_case_t), intent(in) :: rf   !! the case's reference, its RATED cards read
        integer, intent(in) :: m                   !! the rated channel
        if (rf%as_samples(m)) then
            dt = iso18571_dt
        else
            dt = (rf%data%t(2) - rf%data%t(1))*1.0e-3_wp
        end if
    end function rated_interval

    !> ISO 18571 of a volunteer case's rated curves y against the
    !! volunteers' mean on the RATING window (the samples there, at the
    !! volunteers' interval); the rated curves to unit `curves` when present.
    subroutine score_iso_volunteers(cal, c, y, sc, curves)
        type(calibration_t), intent(in) :: cal   !! the calibration
        integer, intent(in) :: c                 !! the case
        real(wp), intent(in) :: y(:, :)          !! (time, channel) the model's rated curves at the volunteers' times
        type(score_t), intent(inout) :: sc       !! its scores: iso filled
        integer, intent(in), optional :: curves  !! unit of the curves' CSV
        integer :: k, i1, i2, stat
        character(len=msglen) :: msg
        associate (vol => cal%vol(c))
            call window_rows(vol%t, cal%window, i1, i2)
            allocate (sc%iso(size(cal%channels)))
            ! the channels' ratings on every core (OpenMP)
            !$omp parallel do schedule(dynamic, 1) private(stat, msg)
            do k = 1, size(cal%channels)
                call iso18571_rating(vol%mean(i1:i2, k), y(i1:i2, k), (vol%t(2) - vol%t(1))*1.0e-3_wp, sc%iso(k), &
                                     stat, msg)
            end do
            !$omp end parallel do
            if (present(curves)) then
                do k = 1, size(cal%channels)
                    call write_curves(curves, c, cal%channels(k)%name, vol%t(i1:i2), vol%mean(i1:i2, k), y(i1:i2, k))
                end do
            end if
        end associate
    end subroutine score_iso_volunteers

    !> Score the rated channels of a reference case: each model curve
    !! (scale (channel - minus), less its start value with START, then
    !! filtered by its CFC class when it has one) at the
    !! reference's times on the rows it is given, by ISO 18571 and the
    !! CORA-style rating (inner corridor half the bounds' width; none
    !! without bounds: the rating's floor); no peaks.
    subroutine score_reference(rf, names, t0, dt, samples, sc, c, curves)
        type(reference_case_t), intent(in) :: rf !! the case's reference
        character(len=*), intent(in) :: names(:) !! channel names of the rows of samples
        real(wp), intent(in) :: t0               !! first sample time [s]
        real(wp), intent(in) :: dt               !! sample interval [s]
        real(wp), intent(in) :: samples(:, :)    !! (nchannel, nsample)
        type(score_t), intent(out) :: sc         !! the scores
        integer, intent(in) :: c                 !! the case's number (the curves' CSV)
        integer, intent(in), optional :: curves  !! unit of the curves' CSV
        real(wp) :: tm(size(samples, 2)), f(size(samples, 2)), g(size(samples, 2)), lag
        real(wp), allocatable :: y(:)
        integer :: m, i, stat
        character(len=msglen) :: msg
        do i = 1, size(tm)
            tm(i) = 1000*(t0 + (i - 1)*dt)
        end do
        m = size(rf%col)
        allocate (sc%rating(m), sc%corridor(m), sc%xcorr(m), sc%iso(m), sc%peak(0), sc%time(0), sc%z(0))
        do m = 1, size(rf%col)
            f = rf%scale(m)*samples(findloc(names, rf%channel(m), dim=1), :)
            if (len_trim(rf%minus(m)) > 0) f = f - rf%scale(m)*samples(findloc(names, rf%minus(m), dim=1), :)
            if (rf%from_start(m)) f = f - f(1)
            if (rf%cfc(m) > zero) then
                g = f
                call cfc_filter(g, dt, rf%cfc(m), f)
            end if
            associate (d => rf%data, k => rf%col(m))
                associate (tr => d%t(d%first(k):d%last(k)), r => d%mean(d%first(k):d%last(k), k))
                    y = resample(tr, tm, f)
                    call iso18571_rating(r, y, rated_interval(rf, m), sc%iso(m), stat, msg)
                    call cora_rating(tr, y, r, (d%upper(d%first(k):d%last(k), k) - d%lower(d%first(k):d%last(k), k))/2, &
                                     [tr(1), tr(size(tr))], sc%corridor(m), sc%xcorr(m), sc%rating(m), lag)
                    if (present(curves)) call write_curves(curves, c, rf%column(m), tr, r, y)
                end associate
            end associate
        end do
    end subroutine score_reference

    !> Score the peaks of a case of published peaks: each PEAK card's peak
    !! of the rated channels (filtered as the volunteers' are) on the run's
    !! own samples, z against the table's mean and SD where it gives the
    !! peak (0 elsewhere); no curve is rated.
    subroutine score_published(cal, c, names, t0, dt, samples, sc)
        type(calibration_t), intent(in) :: cal   !! the calibration
        integer, intent(in) :: c                 !! the case
        character(len=*), intent(in) :: names(:) !! channel names of the rows of samples
        real(wp), intent(in) :: t0               !! first sample time [s]
        real(wp), intent(in) :: dt               !! sample interval [s]
        real(wp), intent(in) :: samples(:, :)    !! (nchannel, nsample)
        type(score_t), intent(out) :: sc         !! the peaks, their times and z
        real(wp) :: tm(size(samples, 2)), y(size(samples, 2), size(cal%channels)), pk(2)
        integer :: i, p
        do i = 1, size(tm)
            tm(i) = 1000*(t0 + (i - 1)*dt)
        end do
        y = rated_histories(cal, tm, names, t0, dt, samples)
        allocate (sc%rating(0), sc%corridor(0), sc%xcorr(0), sc%iso(0), sc%peak(size(cal%peaks)), &
                  sc%time(size(cal%peaks)), sc%z(size(cal%peaks)))
        associate (pb => cal%pub(c))
            do p = 1, size(cal%peaks)
                pk = curve_peak(tm, y(:, cal%peaks(p)%curve), cal%peaks(p)%sign, cal%peaks(p)%window)
                sc%peak(p) = pk(1); sc%time(p) = pk(2)
                sc%z(p) = merge((pk(1) - pb%mean(p))/pb%sd(p), zero, pb%has(p))
            end do
        end associate
    end subroutine score_published

    !> Rows case,channel,time_ms,reference,model of one rated pair of curves.
    subroutine write_curves(u, c, name, t, r, y)
        integer, intent(in) :: u                 !! the CSV's unit
        integer, intent(in) :: c                 !! the case
        character(len=*), intent(in) :: name     !! the channel
        real(wp), intent(in) :: t(:), r(:), y(:) !! times [ms], reference, model
        integer :: i
        do i = 1, size(t)
            write (u, '(i0,a,a,3(a,es24.16e3))') c, ',', trim(name), ',', t(i), ',', r(i), ',', y(i)
        end do
    end subroutine write_curves

    !> The rated channels of a run (the CHANNEL cards), filtered with the
    !! calibration's CFC class and interpolated to the volunteers' times.
    function rated_histories(cal, tv, names, t0, dt, samples) result(y)
        type(calibration_t), intent(in) :: cal   !! the calibration (its channels and filter)
        real(wp), intent(in) :: tv(:)                !! the volunteers' times [ms]
        character(len=*), intent(in) :: names(:)     !! channel names of the rows of samples
        real(wp), intent(in) :: t0               !! first sample time [s]
        real(wp), intent(in) :: dt               !! sample interval [s]
        real(wp), intent(in) :: samples(:, :)        !! (nchannel, nsample)
        real(wp) :: y(size(tv), size(cal%channels))
        real(wp) :: f(size(samples, 2)), tm(size(samples, 2))
        integer :: k, i
        do i = 1, size(tm)
            tm(i) = 1000*(t0 + (i - 1)*dt)
        end do
        do k = 1, size(cal%channels)
            call cfc_filter(samples(findloc(names, cal%channels(k)%name, dim=1), :), dt, cal%cfc, f)
            y(:, k) = resample(tv, tm, f)
        end do
    end function rated_histories

end module hn_calibrate_scores
