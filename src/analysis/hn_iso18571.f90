!> ISO/TS 18571:2014 objective rating of a model curve against a reference
!! curve ("Road vehicles -- Objective rating metric for non-ambiguous
!! signals"): corridor score Z, phase score E_P, magnitude score E_M and
!! slope score E_S, and the overall rating R = w_Z Z + w_P E_P + w_M E_M +
!! w_S E_S. The formulas and every choice below are those of the standard's
!! published implementation, the PyPI package objective-rating-metrics 1.3
!! (TU Graz, MIT; class ISO18571 and its defaults), which tools/iso18571.py
!! calls and test/unit/test_iso18571.pf agrees with.
!!
!! With N samples r (reference) and m (model) at 10 kHz:
!!   Corridor (on the curves as given, not shifted): t_norm = max|r|,
!!     inner half-width a_0 t_norm, outer b_0 t_norm; a sample scores 1 if
!!     |m - r| < a_0 t_norm, 0 if |m - r| > b_0 t_norm, else
!!     ((b_0 t_norm - |m - r|)/((b_0 - a_0) t_norm))^k_z; Z is the mean.
!!   Phase: the Pearson correlation of r and m shifted against each other by
!!     k = 0, 1, ..., floor(eps_P* N) samples, for each k first the model
!!     moved earlier (r(1:N-k) with m(1+k:N), a late model) and then later;
!!     a shift replaces the best so far only when its correlation is
!!     strictly greater (the smallest shift wins a tie, the late model
!!     before the early one). With n_eps the best shift: E_P = 1 if
!!     n_eps = 0, 0 if n_eps >= eps_P* N, else ((eps_P* N - n_eps)/(eps_P* N))^k_p.
!!     A correlation that is undefined (a constant segment) is never the
!!     best; when the unshifted one is undefined no shift is made (numpy's
!!     NaN comparisons in the package).
!!   Magnitude (on the shifted curves, both of length L): dynamic time
!!     warping of the model x against the reference y with the squared
!!     difference as the local cost, the steps (i-1,j), (i,j-1), (i-1,j-1)
!!     of weight 1 (no normalization) inside a Sakoe-Chiba band
!!     |i - j| <= ceiling(0.1 L) - 1 (the package's window of 10 % minus
!!     one, as it hands dtwalign its size), the path traced back from
!!     (L,L) taking at each step the first smallest accumulated cost in the
!!     order (i-1,j), (i,j-1), (i-1,j-1) (dtwalign 0.1.1); along the path
!!     eps_M = sum|x - y| / sum|y|, E_M = 1 if eps_M = 0, 0 if eps_M > eps_M*,
!!     else ((eps_M* - eps_M)/eps_M*)^k_m.
!!   Slope (on the shifted curves): the derivative by central differences
!!     (one-sided at the two ends, numpy.gradient) smoothed by a 9-sample
!!     moving mean, at the first and last four samples by the mean of the
!!     first (last) 1, 3, 5, 7 samples of the derivative; eps_S = sum|x' -
!!     y'| / sum|y'|, E_S = 1 if eps_S <= 0, 0 if eps_S >= eps_S*, else
!!     ((eps_S* - eps_S)/eps_S*)^k_s. The package has no exponent k_s (it is
!!     1, the standard's value) and takes dt = 0.1 ms for the derivative;
!!     eps_S does not depend on dt.
!! Choices of the package followed here:
!!   - sampling: the package does no interpolation and asks for 10 kHz;
!!     curves at another interval dt are interpolated linearly (numpy.interp)
!!     onto t = k 0.1 ms, k = 0 .. floor((N - 1) dt / 0.1 ms + 1e-6), as
!!     tools/iso18571.py does; curves at 0.1 ms (to 1e-9 of it) are used as
!!     they are;
!!   - the DTW band and tie order above; the phase search's order and ties;
!!   - rounding: the package rounds each score to 3 digits by default (the
!!     overall rating from the unrounded scores); the scores here are not
!!     rounded.
!! Memory: the DTW keeps the band, L (2 ceiling(0.1 L) - 1) reals (at 10 kHz,
!! 0.3 s of curve: 24 MB).
module hn_iso18571
    use hn_kinds, only: wp, zero, one, two
    use hn_status, only: stat_ok, stat_bad_input
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    implicit none
    private

    public :: iso18571_rating_t, iso18571_rating, iso18571_resample
    public :: iso18571_dt, iso18571_k_z, iso18571_k_p, iso18571_k_m, iso18571_k_s, iso18571_a_0, iso18571_b_0, &
              iso18571_eps_p, iso18571_eps_m, iso18571_eps_s, iso18571_dtw_window, &
              iso18571_w_z, iso18571_w_p, iso18571_w_m, iso18571_w_s, iso18571_min_samples

    ! The standard's parameter values (ISO/TS 18571:2014), as the defaults of
    ! objective-rating-metrics 1.3, class ISO18571:
    real(wp), parameter :: iso18571_dt = 1.0e-4_wp      !! sampling interval of the rating: 10 kHz [s]
    integer, parameter :: iso18571_k_z = 2              !! corridor score exponent k_z
    integer, parameter :: iso18571_k_p = 1              !! phase score exponent k_p
    integer, parameter :: iso18571_k_m = 1              !! magnitude score exponent k_m
    integer, parameter :: iso18571_k_s = 1              !! slope score exponent k_s
    real(wp), parameter :: iso18571_a_0 = 0.05_wp       !! inner corridor half-width, relative to max|reference|
    real(wp), parameter :: iso18571_b_0 = 0.5_wp        !! outer corridor half-width, relative to max|reference|
    real(wp), parameter :: iso18571_eps_p = 0.2_wp      !! largest time shift eps_P*, a fraction of the samples (package: 1 - 0.8)
    real(wp), parameter :: iso18571_eps_m = 0.5_wp      !! magnitude error eps_M* that scores 0
    real(wp), parameter :: iso18571_eps_s = 2.0_wp      !! slope error eps_S* that scores 0
    real(wp), parameter :: iso18571_dtw_window = 0.1_wp !! Sakoe-Chiba band of the DTW, a fraction of the samples
    real(wp), parameter :: iso18571_w_z = 0.4_wp        !! weight of the corridor score
    real(wp), parameter :: iso18571_w_p = 0.2_wp        !! weight of the phase score
    real(wp), parameter :: iso18571_w_m = 0.2_wp        !! weight of the magnitude score
    real(wp), parameter :: iso18571_w_s = 0.2_wp        !! weight of the slope score
    integer, parameter :: iso18571_min_samples = 16     !! fewest samples at 10 kHz that are rated (the 9-sample smoothing)

    integer, parameter :: nsmooth = 9                   ! the slope's moving mean

    !> The four scores and the overall rating, each in [0, 1], unrounded.
    type :: iso18571_rating_t
        real(wp) :: corridor = zero    !! corridor score Z
        real(wp) :: phase = zero       !! phase score E_P
        real(wp) :: magnitude = zero   !! magnitude score E_M
        real(wp) :: slope = zero       !! slope score E_S
        real(wp) :: overall = zero     !! weighted overall rating R
        real(wp) :: shift = zero       !! time shift of the best correlation [s]; > 0 when the model lags
    end type iso18571_rating_t

contains

    !> ISO/TS 18571 rating of `model` against `reference`, both sampled at the
    !! same interval `dt` from the same start (the interval of evaluation);
    !! resampled to 10 kHz when dt is not 0.1 ms. `stat` is stat_bad_input,
    !! with a message, for curves of different lengths, a dt that is not
    !! positive, values that are not finite, fewer than 16 samples at 10 kHz,
    !! or a reference that is zero or constant (nothing to rate against).
    pure subroutine iso18571_rating(reference, model, dt, rating, stat, errmsg)
        real(wp), intent(in) :: reference(:)            !! reference curve (a test, a corridor's mean)
        real(wp), intent(in) :: model(:)                !! model curve, at the same times
        real(wp), intent(in) :: dt                      !! sampling interval of both [s]
        type(iso18571_rating_t), intent(out) :: rating  !! the scores (zero when stat /= stat_ok)
        integer, intent(out) :: stat                    !! stat_ok or stat_bad_input
        character(len=*), intent(out) :: errmsg         !! why, when stat /= stat_ok; blank otherwise
        real(wp), allocatable :: r(:), m(:)
        integer :: n, k_eps, late, lo_r, hi_r, lo_m, hi_m
        real(wp) :: e_mag, e_slope, thr

        stat = stat_bad_input
        errmsg = ''
        if (size(reference) /= size(model)) then
            errmsg = 'ISO 18571 rating: the reference and the model have different numbers of samples'
            return
        end if
        if (size(reference) < 2) then
            errmsg = 'ISO 18571 rating: fewer than two samples'
            return
        end if
        if (.not. (dt > zero) .or. .not. ieee_is_finite(dt)) then
            errmsg = 'ISO 18571 rating: the sampling interval is not positive'
            return
        end if
        if (.not. all(ieee_is_finite(reference)) .or. .not. all(ieee_is_finite(model))) then
            errmsg = 'ISO 18571 rating: a value is not finite'
            return
        end if
        call iso18571_resample(reference, dt, r)
        call iso18571_resample(model, dt, m)
        n = size(r)
        if (n < iso18571_min_samples) then
            write (errmsg, '(a,i0,a,i0,a)') 'ISO 18571 rating: ', n, ' samples at 10 kHz, at least ', &
                iso18571_min_samples, ' needed'
            return
        end if
        if (maxval(abs(r)) == zero .or. maxval(r) == minval(r)) then
            errmsg = 'ISO 18571 rating: the reference curve is zero or constant: nothing to rate against'
            return
        end if

        rating%corridor = corridor_score(r, m)

        call best_shift(r, m, k_eps, late)
        if (late > 0) then          ! model later: r(1:n-k) against m(1+k:n)
            lo_r = 1; hi_r = n - k_eps; lo_m = 1 + k_eps; hi_m = n
        else                        ! model earlier (or no shift)
            lo_r = 1 + k_eps; hi_r = n; lo_m = 1; hi_m = n - k_eps
        end if
        rating%shift = real(late*k_eps, wp)*iso18571_dt
        thr = real(n, wp)*iso18571_eps_p
        if (k_eps == 0) then
            rating%phase = one
        else if (real(k_eps, wp) >= thr) then
            rating%phase = zero
        else
            rating%phase = ((thr - real(k_eps, wp))/thr)**iso18571_k_p
        end if

        e_mag = dtw_magnitude_error(m(lo_m:hi_m), r(lo_r:hi_r))
        if (e_mag < zero) then
            errmsg = 'ISO 18571 rating: the shifted reference curve is zero: no magnitude error'
            return
        end if
        if (e_mag == zero) then
            rating%magnitude = one
        else if (e_mag > iso18571_eps_m) then
            rating%magnitude = zero
        else
            rating%magnitude = ((iso18571_eps_m - e_mag)/iso18571_eps_m)**iso18571_k_m
        end if

        e_slope = slope_error(m(lo_m:hi_m), r(lo_r:hi_r))
        if (e_slope < zero) then
            errmsg = 'ISO 18571 rating: the shifted reference curve is constant: no slope error'
            return
        end if
        if (e_slope <= zero) then
            rating%slope = one
        else if (e_slope >= iso18571_eps_s) then
            rating%slope = zero
        else
            rating%slope = ((iso18571_eps_s - e_slope)/iso18571_eps_s)**iso18571_k_s
        end if

        rating%overall = iso18571_w_z*rating%corridor + iso18571_w_p*rating%phase + &
                         iso18571_w_m*rating%magnitude + iso18571_w_s*rating%slope
        stat = stat_ok
    end subroutine iso18571_rating

    !> `x` sampled at `dt` from t = 0, at 10 kHz: `y` = x when dt is 0.1 ms
    !! (to 1e-9 of it), else linearly interpolated at t = k 0.1 ms,
    !! k = 0 .. floor((size(x) - 1) dt / 0.1 ms + 1e-6) (numpy.interp's
    !! arithmetic: a sample time's own value, else slope (t - t_j) + x_j).
    pure subroutine iso18571_resample(x, dt, y)
        real(wp), intent(in) :: x(:)                 !! samples at t = (i - 1) dt, at least two
        real(wp), intent(in) :: dt                   !! their interval [s], positive
        real(wp), allocatable, intent(out) :: y(:)   !! the samples at 10 kHz
        integer :: n, nnew, k, j
        real(wp) :: t, tj, tj1
        n = size(x)
        if (abs(dt - iso18571_dt) <= 1.0e-9_wp*iso18571_dt .or. n < 2) then
            y = x
            return
        end if
        nnew = floor(real(n - 1, wp)*dt/iso18571_dt + 1.0e-6_wp) + 1
        allocate (y(nnew))
        j = 0                                        ! 0-based: t_j = j dt <= t < t_(j+1)
        do k = 1, nnew
            t = iso18571_dt*real(k - 1, wp)
            do while (j < n - 1)
                if (real(j + 1, wp)*dt > t) exit
                j = j + 1
            end do
            tj = real(j, wp)*dt
            if (j >= n - 1) then
                y(k) = x(n)
            else if (tj == t) then
                y(k) = x(j + 1)
            else
                tj1 = real(j + 1, wp)*dt
                y(k) = (x(j + 2) - x(j + 1))/(tj1 - tj)*(t - tj) + x(j + 1)
            end if
        end do
    end subroutine iso18571_resample

    ! Mean corridor score of m against r (unshifted).
    pure function corridor_score(r, m) result(z)
        real(wp), intent(in) :: r(:), m(:)
        real(wp) :: z
        real(wp) :: inner, outer, d, c
        integer :: i
        inner = iso18571_a_0*maxval(abs(r))
        outer = iso18571_b_0*maxval(abs(r))
        z = zero
        do i = 1, size(r)
            d = abs(r(i) - m(i))
            if (d < inner) then
                c = one
            else if (d > outer) then
                c = zero
            else
                c = ((outer - d)/(outer - inner))**iso18571_k_z
            end if
            z = z + c
        end do
        z = z/real(size(r), wp)
    end function corridor_score

    ! Pearson correlation of x and y as numpy.corrcoef computes it (the
    ! covariance over n - 1, divided by each standard deviation in turn,
    ! clipped to [-1, 1]); defined = .false. when either is constant.
    pure subroutine correlation(x, y, rho, defined)
        real(wp), intent(in) :: x(:), y(:)
        real(wp), intent(out) :: rho
        logical, intent(out) :: defined
        real(wp) :: mx, my, sxx, syy, sxy, f
        integer :: i, n
        n = size(x)
        mx = sum(x)/real(n, wp)
        my = sum(y)/real(n, wp)
        sxx = zero; syy = zero; sxy = zero
        do i = 1, n
            sxx = sxx + (x(i) - mx)**2
            syy = syy + (y(i) - my)**2
            sxy = sxy + (x(i) - mx)*(y(i) - my)
        end do
        defined = sxx > zero .and. syy > zero
        rho = zero
        if (.not. defined) return
        f = one/real(n - 1, wp)
        rho = sxy*f/sqrt(sxx*f)/sqrt(syy*f)
        rho = max(-one, min(one, rho))
    end subroutine correlation

    ! The shift of the largest correlation (the package's search, module
    ! header): k_eps samples, late = +1 when the model lags, -1 when it
    ! leads, 0 for no shift.
    pure subroutine best_shift(r, m, k_eps, late)
        real(wp), intent(in) :: r(:), m(:)
        integer, intent(out) :: k_eps, late
        real(wp) :: best, rho
        logical :: have, defined
        integer :: n, k
        n = size(r)
        k_eps = 0
        late = 0
        call correlation(r, m, best, have)
        if (.not. have) return
        do k = 1, floor(real(n, wp)*iso18571_eps_p)
            call correlation(r(1:n - k), m(1 + k:n), rho, defined)
            if (defined .and. rho > best) then
                best = rho; k_eps = k; late = 1
            end if
            call correlation(r(1 + k:n), m(1:n - k), rho, defined)
            if (defined .and. rho > best) then
                best = rho; k_eps = k; late = -1
            end if
        end do
    end subroutine best_shift

    ! The magnitude error sum|x - y|/sum|y| along the DTW path of x (model)
    ! against y (reference) (module header); -1 when sum|y| is zero.
    pure function dtw_magnitude_error(x, y) result(e)
        real(wp), intent(in) :: x(:), y(:)
        real(wp) :: e
        real(wp), allocatable :: d(:, :)     ! d(j - i, i): accumulated cost of cell (i, j), 0-based
        integer :: n, w, i, j, pick
        real(wp) :: cost, best, num, den
        logical :: have
        n = size(x)
        w = ceiling(iso18571_dtw_window*real(n, wp)) - 1
        allocate (d(-w:w, 0:n - 1))
        d = zero
        do i = 0, n - 1
            do j = max(0, i - w), min(n - 1, i + w)
                cost = (x(i + 1) - y(j + 1))**2
                if (i == 0 .and. j == 0) then
                    d(0, 0) = cost
                    cycle
                end if
                have = .false.
                best = zero
                if (inside(i - 1, j)) call consider(d(j - i + 1, i - 1) + cost, have, best)
                if (inside(i, j - 1)) call consider(d(j - 1 - i, i) + cost, have, best)
                if (inside(i - 1, j - 1)) call consider(d(j - i, i - 1) + cost, have, best)
                d(j - i, i) = best
            end do
        end do
        ! back from (n-1, n-1) to (0, 0): the first smallest of (i-1,j), (i,j-1), (i-1,j-1)
        i = n - 1; j = n - 1
        num = abs(x(i + 1) - y(j + 1)); den = abs(y(j + 1))
        do while (i > 0 .or. j > 0)
            pick = 0
            if (inside(i - 1, j)) then
                pick = 1; best = d(j - i + 1, i - 1)
            end if
            if (inside(i, j - 1)) then
                if (pick == 0 .or. d(j - 1 - i, i) < best) then
                    pick = 2; best = d(j - 1 - i, i)
                end if
            end if
            if (inside(i - 1, j - 1)) then
                if (pick == 0 .or. d(j - i, i - 1) < best) then
                    pick = 3; best = d(j - i, i - 1)
                end if
            end if
            select case (pick)
            case (1); i = i - 1
            case (2); j = j - 1
            case default; i = i - 1; j = j - 1
            end select
            num = num + abs(x(i + 1) - y(j + 1))
            den = den + abs(y(j + 1))
        end do
        if (den == zero) then
            e = -one
        else
            e = num/den
        end if
    contains
        pure logical function inside(ii, jj)
            integer, intent(in) :: ii, jj
            inside = ii >= 0 .and. jj >= 0 .and. abs(ii - jj) <= w
        end function inside
        pure subroutine consider(c, have, best)
            real(wp), intent(in) :: c
            logical, intent(inout) :: have
            real(wp), intent(inout) :: best
            if (.not. have .or. c < best) best = c
            have = .true.
        end subroutine consider
    end function dtw_magnitude_error

    ! The slope error sum|x' - y'|/sum|y'| of the smoothed derivatives
    ! (module header); -1 when sum|y'| is zero.
    pure function slope_error(x, y) result(e)
        real(wp), intent(in) :: x(:), y(:)
        real(wp) :: e
        real(wp) :: dx(size(x)), dy(size(y))
        real(wp) :: den
        call smoothed_derivative(x, dx)
        call smoothed_derivative(y, dy)
        den = sum(abs(dy))
        if (den == zero) then
            e = -one
        else
            e = sum(abs(dx - dy))/den
        end if
    end function slope_error

    ! numpy.gradient at the package's dt, then the 9-sample moving mean with
    ! the means of the first and last 1, 3, 5, 7 samples at the ends.
    pure subroutine smoothed_derivative(f, s)
        real(wp), intent(in) :: f(:)
        real(wp), intent(out) :: s(:)
        real(wp) :: g(size(f))
        integer :: n, i, k, nr
        n = size(f)
        g(1) = (f(2) - f(1))/iso18571_dt
        g(n) = (f(n) - f(n - 1))/iso18571_dt
        do i = 2, n - 1
            g(i) = (f(i + 1) - f(i - 1))/(two*iso18571_dt)
        end do
        do k = 0, 3
            nr = 2*k + 1
            s(1 + k) = one/real(nr, wp)*sum(g(1:nr))
            s(n - k) = one/real(nr, wp)*sum(g(n - nr + 1:n))
        end do
        do i = 5, n - 4
            s(i) = sum(g(i - 4:i + 4)*(one/real(nsmooth, wp)))
        end do
    end subroutine smoothed_derivative

end module hn_iso18571
