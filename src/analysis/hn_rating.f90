!> The CORA-style rating of a curve against a corridor (the point-wise mean
!! and SD of a set of runs) and the peaks of curves, generic: what the
!! curves are, which window is rated and where each peak is looked for
!! come from the caller (the calibration deck: docs/sweeps.md). Times in
!! ms. The rating is that of tools/compare_nbdl.py (docs/validation.md):
!!
!! * corridor rating c: the mean over the window of 1 where |y - mean| is
!!   within the inner corridor max(SD, 5 % of the largest |mean|), 0
!!   beyond the outer corridor (three times the inner), and
!!   ((outer - d)/(outer - inner))**2 between;
!! * cross-correlation rating x = (phase + shape + size)/3: the lag of the
!!   best Pearson correlation within +-30 ms, phase 1 up to 2 ms and falling
!!   linearly to 0 at 30 ms; shape ((1 + rho)/2)**2; size the ratio of the
!!   smaller to the larger sum of squares;
!! * rating (c + x)/2.
module hn_rating
    use hn_kinds, only: wp, zero, one
    use hn_iso18571, only: iso18571_rating_t
    implicit none
    private

    public :: peak_t, corridor_t, score_t, cora_rating, curve_peak, runs_corridor, score_curves, window_samples

    real(wp), parameter, public :: max_lag = 30.0_wp     !! largest lag of the cross-correlation [ms]
    real(wp), parameter :: free_lag = 2.0_wp             !! lag with the full phase rating [ms]
    real(wp), parameter :: floor_share = 0.05_wp         !! inner corridor at least this share of the largest |mean|
    real(wp), parameter :: outer_factor = 3.0_wp         !! outer corridor / inner corridor

    !> A peak of one curve of a set: its signed extreme within a window.
    type :: peak_t
        character(len=16) :: name = ''      !! its name in listings
        integer :: curve = 0                !! which curve of the set
        real(wp) :: sign = one              !! +1 the maximum, -1 the minimum
        real(wp) :: window(2) = zero        !! where it is looked for [ms]
    end type peak_t

    !> A corridor: a set of runs of several curves at common times, their
    !! point-wise mean and SD, and the mean and SD of the runs' peaks and
    !! peak times.
    type :: corridor_t
        real(wp), allocatable :: t(:)                       !! times [ms]
        real(wp), allocatable :: mean(:, :), sd(:, :)       !! (time, curve)
        real(wp), allocatable :: peak_mean(:), peak_sd(:)   !! (peak) [curve units]
        real(wp), allocatable :: time_mean(:), time_sd(:)   !! (peak) [ms]
        integer :: nrun = 0
    end type corridor_t

    !> How a set of curves compares with a corridor.
    type :: score_t
        real(wp), allocatable :: rating(:)       !! (curve) CORA-style rating
        real(wp), allocatable :: corridor(:)     !! (curve) corridor rating
        real(wp), allocatable :: xcorr(:)        !! (curve) cross-correlation rating
        type(iso18571_rating_t), allocatable :: iso(:) !! (curve) ISO/TS 18571 scores (filled by the caller)
        real(wp), allocatable :: peak(:)         !! (peak) the curves' peaks [curve units]
        real(wp), allocatable :: time(:)         !! (peak) their times [ms]
        real(wp), allocatable :: z(:)            !! (peak) (peak - corridor's mean peak)/its SD
    end type score_t

contains

    !> CORA-style rating of y against the corridor mean r and SD s on the
    !! window (the module's description): corridor rating c,
    !! cross-correlation rating x, rating (c + x)/2, lag [ms]. The window
    !! holds more than max_lag/dt + 1 samples (window_samples).
    pure subroutine cora_rating(t, y, r, s, window, c, x, rating, lag)
        real(wp), intent(in) :: t(:)             !! times [ms], evenly spaced
        real(wp), intent(in) :: y(:)             !! the curve at t
        real(wp), intent(in) :: r(:)             !! the corridor's mean at t
        real(wp), intent(in) :: s(:)             !! its SD at t
        real(wp), intent(in) :: window(2)        !! the rated times, first and last [ms]
        real(wp), intent(out) :: c               !! corridor rating
        real(wp), intent(out) :: x               !! cross-correlation rating
        real(wp), intent(out) :: rating          !! CORA-style rating (c + x)/2
        real(wp), intent(out) :: lag             !! lag of the best correlation [ms]
        logical :: m(size(t))
        real(wp), allocatable :: yw(:), rw(:), sw(:), inner(:), outer(:), d(:), cs(:)
        real(wp) :: floor, dt, best, rho, ep, ev, es, shift
        integer :: n, k, maxlag, lo, hi, kbest
        m = t >= window(1) .and. t <= window(2)
        yw = pack(y, m); rw = pack(r, m); sw = pack(s, m)
        n = size(yw)
        floor = floor_share*maxval(abs(rw))
        inner = max(sw, floor)
        outer = max(outer_factor*sw, outer_factor*floor)
        d = abs(yw - rw)
        allocate (cs(n))
        where (d <= inner)
            cs = one
        elsewhere (d >= outer)
            cs = zero
        elsewhere
            cs = ((outer - d)/(outer - inner))**2
        end where
        c = sum(cs)/n
        dt = t(2) - t(1)
        maxlag = nint(max_lag/dt)
        best = -2; kbest = 0
        do k = -maxlag, maxlag
            lo = max(0, k); hi = n + min(0, k)
            rho = pearson(yw(lo - k + 1:hi - k), rw(lo + 1:hi))
            if (rho > best) then
                best = rho; kbest = k
            end if
        end do
        shift = abs(kbest)*dt
        ep = one
        if (shift > free_lag) ep = max(zero, (max_lag - shift)/(max_lag - free_lag))
        ev = ((one + best)/2)**2
        es = min(sum(yw**2), sum(rw**2))/max(sum(yw**2), sum(rw**2))
        x = (ep + ev + es)/3
        rating = 0.5_wp*c + 0.5_wp*x
        lag = kbest*dt
    end subroutine cora_rating

    pure real(wp) function pearson(a, b) result(rho)
        real(wp), intent(in) :: a(:), b(:)
        real(wp) :: da(size(a)), db(size(b))
        da = a - sum(a)/size(a)
        db = b - sum(b)/size(b)
        rho = sum(da*db)/sqrt(sum(da**2)*sum(db**2))
    end function pearson

    !> The number of the times t within the window, and the fewest the
    !! rating needs on times spaced as t (more than max_lag/dt + 1: every
    !! lag leaves two samples to correlate).
    pure subroutine window_samples(t, window, n, nmin)
        real(wp), intent(in) :: t(:)             !! times [ms], evenly spaced, at least two
        real(wp), intent(in) :: window(2)        !! first and last rated time [ms]
        integer, intent(out) :: n                !! times within the window
        integer, intent(out) :: nmin             !! fewest the rating needs
        n = count(t >= window(1) .and. t <= window(2))
        nmin = nint(max_lag/(t(2) - t(1))) + 2
    end subroutine window_samples

    !> Signed extreme of x (sign +1: maximum, -1: minimum) within the
    !! window, and its time: [value, time]; the first of equal extremes. The
    !! window holds at least one of the times t.
    pure function curve_peak(t, x, sign, window) result(pk)
        real(wp), intent(in) :: t(:)             !! times [ms]
        real(wp), intent(in) :: x(:)             !! the curve at t
        real(wp), intent(in) :: sign             !! +1 the maximum, -1 the minimum
        real(wp), intent(in) :: window(2)        !! first and last time searched [ms]
        real(wp) :: pk(2)
        integer :: i, ibest
        ibest = 0
        do i = 1, size(t)
            if (t(i) < window(1) .or. t(i) > window(2)) cycle
            if (ibest == 0) then
                ibest = i
            else if (sign*x(i) > sign*x(ibest)) then
                ibest = i
            end if
        end do
        pk = [x(ibest), t(ibest)]
    end function curve_peak

    !> The corridor of a set of runs: point-wise mean and sample SD of each
    !! curve over the runs, and the mean and sample SD of each peak's value
    !! and time over the runs. At least two runs.
    pure function runs_corridor(t, runs, peaks) result(cor)
        real(wp), intent(in) :: t(:)             !! times [ms]
        real(wp), intent(in) :: runs(:, :, :)    !! (time, run, curve)
        type(peak_t), intent(in) :: peaks(:)     !! the peaks (curve numbers the third index of runs)
        type(corridor_t) :: cor
        real(wp) :: pks(2, size(runs, 2))
        integer :: nt, k, p, r
        nt = size(t)
        cor%t = t
        cor%nrun = size(runs, 2)
        allocate (cor%mean(nt, size(runs, 3)), cor%sd(nt, size(runs, 3)))
        associate (ch => runs, n => cor%nrun)
            do k = 1, size(runs, 3)
                cor%mean(:, k) = sum(ch(:, :, k), dim=2)/n
                cor%sd(:, k) = sqrt(sum((ch(:, :, k) - spread(cor%mean(:, k), 2, n))**2, dim=2)/(n - 1))
            end do
            allocate (cor%peak_mean(size(peaks)), cor%peak_sd(size(peaks)), cor%time_mean(size(peaks)), &
                      cor%time_sd(size(peaks)))
            do p = 1, size(peaks)
                do r = 1, n
                    pks(:, r) = curve_peak(t, ch(:, r, peaks(p)%curve), peaks(p)%sign, peaks(p)%window)
                end do
                cor%peak_mean(p) = sum(pks(1, :))/n
                cor%peak_sd(p) = sqrt(sum((pks(1, :) - cor%peak_mean(p))**2)/(n - 1))
                cor%time_mean(p) = sum(pks(2, :))/n
                cor%time_sd(p) = sqrt(sum((pks(2, :) - cor%time_mean(p))**2)/(n - 1))
            end do
        end associate
    end function runs_corridor

    !> Score curves y (at the corridor's times) against the corridor: the
    !! CORA-style rating of each curve on the window, each peak and its
    !! distance z from the corridor's mean peak in SDs.
    pure subroutine score_curves(cor, y, window, peaks, sc)
        type(corridor_t), intent(in) :: cor      !! the corridor
        real(wp), intent(in) :: y(:, :)          !! (time, curve) the curves at cor%t
        real(wp), intent(in) :: window(2)        !! the rated times, first and last [ms]
        type(peak_t), intent(in) :: peaks(:)     !! the peaks, as for the corridor
        type(score_t), intent(out) :: sc         !! ratings and peaks
        real(wp) :: lag, pk(2)
        integer :: k, p, nc, np
        nc = size(y, 2); np = size(peaks)
        allocate (sc%rating(nc), sc%corridor(nc), sc%xcorr(nc), sc%peak(np), sc%time(np), sc%z(np))
        do k = 1, nc
            call cora_rating(cor%t, y(:, k), cor%mean(:, k), cor%sd(:, k), window, sc%corridor(k), sc%xcorr(k), &
                             sc%rating(k), lag)
        end do
        do p = 1, np
            pk = curve_peak(cor%t, y(:, peaks(p)%curve), peaks(p)%sign, peaks(p)%window)
            sc%peak(p) = pk(1); sc%time(p) = pk(2)
            sc%z(p) = (pk(1) - cor%peak_mean(p))/cor%peak_sd(p)
        end do
    end subroutine score_curves

end module hn_rating
