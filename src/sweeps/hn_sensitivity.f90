!> Sensitivity measures from the member runs of a sweep.
!!
!! One-at-a-time designs give the normalised sensitivity (elasticity)
!!     S = [(y+ - y-)/(2 y0)] / (step/100)
!! by central differences: the percentage change of an output per percent
!! change of the parameter. Factorial and Latin-hypercube designs give
!! standardised regression coefficients: the least-squares fit of the
!! standardised output on the standardised inputs (the logarithm of inputs
!! spaced LOG), solved from the normal equations R_xx b = r_xy by Gaussian
!! elimination; R^2 = b . r_xy tells how much of the output's variance the
!! linear model explains (Saltelli et al., Sensitivity Analysis in Practice,
!! 2004, ch. 1).
module hn_sensitivity
    use hn_kinds, only: wp, zero, one, two
    use hn_linsolve, only: gauss_solve
    implicit none
    private

    public :: oat_sensitivity, regression_sensitivity, roundoff_outputs

    !> An output is roundoff when its largest magnitude over the members is
    !! at most this fraction of its group's (the listing comparison's noise
    !! level: the out-of-plane loads of a sagittal run are about 1E-14 of
    !! the in-plane ones).
    real(wp), parameter, public :: roundoff_level = 1.0e-8_wp

contains

    !> Elasticities s(p) of one output from a one-at-a-time design: run 1
    !! nominal, runs 2p and 2p+1 parameter p at -step and +step percent.
    !! valid(p) is false when one of the three runs failed or y0 is zero.
    pure subroutine oat_sensitivity(y, ok, percent, s, valid)
        real(wp), intent(in) :: y(:)         !! output of every run
        logical, intent(in) :: ok(:)         !! run completed
        real(wp), intent(in) :: percent      !! step [%]
        real(wp), intent(out) :: s(:)        !! one per parameter
        logical, intent(out) :: valid(:)     !! s(p) could be computed (its three runs complete, y0 /= 0)
        integer :: p
        do p = 1, size(s)
            valid(p) = ok(1) .and. ok(2*p) .and. ok(2*p + 1) .and. abs(y(1)) > tiny(one)
            s(p) = zero
            if (valid(p)) s(p) = (y(2*p + 1) - y(2*p))/(two*y(1))/(percent/100.0_wp)
        end do
    end subroutine oat_sensitivity

    !> Standardised regression coefficients b(p) of one output on the inputs
    !! x(p, r) over the completed runs, and the R^2 of the fit. valid is
    !! false with fewer completed runs than parameters + 2, a constant output
    !! or input, or a singular correlation matrix.
    pure subroutine regression_sensitivity(x, y, ok, b, r2, valid)
        real(wp), intent(in) :: x(:, :)      !! (np, nrun) inputs (already log where LOG)
        real(wp), intent(in) :: y(:)         !! (nrun) output
        logical, intent(in) :: ok(:)         !! run completed
        real(wp), intent(out) :: b(:)        !! (np)
        real(wp), intent(out) :: r2          !! R^2 of the fit (fraction of the output's variance explained)
        logical, intent(out) :: valid        !! b and r2 could be computed
        real(wp), allocatable :: z(:, :), w(:), rxx(:, :), rxy(:)
        real(wp) :: sd
        integer :: np, n, p, stat
        np = size(x, 1)
        b = zero; r2 = zero; valid = .false.
        n = count(ok)
        if (n < np + 2) return
        allocate (z(np, n), w(n))
        do p = 1, np
            z(p, :) = pack(x(p, :), ok)
        end do
        w = pack(y, ok)
        ! standardise
        do p = 1, np
            z(p, :) = z(p, :) - sum(z(p, :))/n
            sd = sqrt(sum(z(p, :)**2)/(n - 1))
            if (.not. sd > zero) return
            z(p, :) = z(p, :)/sd
        end do
        w = w - sum(w)/n
        sd = sqrt(sum(w**2)/(n - 1))
        if (.not. sd > 1.0e-12_wp*max(one, maxval(abs(pack(y, ok))))) return
        w = w/sd
        ! correlations and the normal equations
        rxx = matmul(z, transpose(z))/(n - 1)
        rxy = matmul(z, w)/(n - 1)
        b = rxy
        call gauss_solve(rxx, b, stat)
        if (stat /= 0) then
            b = zero
            return
        end if
        r2 = dot_product(b, rxy)
        valid = .true.
    end subroutine regression_sensitivity

    !> Outputs that are only roundoff over the completed members (e.g. the
    !! lateral outputs of a frontal sweep): the largest magnitude of output
    !! ref(k) is at most roundoff_level times the largest magnitude of any
    !! output of its group (itself alone for group 0); an output that is
    !! zero in every member, or with no completed member, is roundoff too.
    !! Their sensitivities are undefined (elasticities and regression
    !! coefficients of roundoff would be numbers without meaning).
    pure function roundoff_outputs(y, ok, ref, group) result(noise)
        real(wp), intent(in) :: y(:, :)      !! (nout, nrun) outputs of every member
        logical, intent(in) :: ok(:)         !! (nrun) run completed
        integer, intent(in) :: ref(:)        !! (nout) the output whose magnitude decides for output k
        integer, intent(in) :: group(:)      !! (nout) outputs of one quantity share a positive group number
        logical :: noise(size(y, 1))
        real(wp) :: big(size(y, 1)), scale
        integer :: k, r
        do k = 1, size(y, 1)
            big(k) = maxval(abs(y(k, :)), mask=ok)
            if (.not. any(ok)) big(k) = zero
        end do
        do k = 1, size(y, 1)
            r = ref(k)
            scale = big(r)
            if (group(r) > 0) scale = maxval(big, mask=group == group(r))
            noise(k) = .not. big(r) > roundoff_level*scale
        end do
    end function roundoff_outputs

end module hn_sensitivity
