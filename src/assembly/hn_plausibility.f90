!> Physical plausibility of a valid deck: warnings, not errors. Masses and
!! principal inertias far below the vertebral range (runs that crawl), inertia
!! that violates the triangle inequality of principal moments, attachment
!! points far outside their body, and element stiffness two orders of
!! magnitude or more away from the reference model's (reference/parameters.md).
module hn_plausibility
    use hn_kinds, only: wp, zero, half
    use hn_model, only: model_t
    use hn_element_family, only: warning_len, add_warning, check_point
    implicit none
    private

    public :: plausibility_warnings

    ! the element families' checks are their `plausibility` bindings (hn_element_family)
    real(wp), parameter :: light_mass = 0.01_wp           !! kg: ~40x below the lightest vertebra (0.376 kg)
    real(wp), parameter :: small_inertia = 1.0e-6_wp      !! kg m^2: ~300x below the smallest vertebral moment

contains

    !> Warnings about the model, one line each.
    subroutine plausibility_warnings(model, warnings)
        type(model_t), intent(in) :: model                            !! the model as read from the deck
        character(len=warning_len), allocatable, intent(out) :: warnings(:)   !! one line per doubtful value (none: size 0)
        integer :: k, e, f
        real(wp) :: ev(3)
        character(len=160) :: w
        character(len=300) :: wl
        allocate (warnings(0))
        associate (t => model%tree)
            do k = 1, t%nbody
                if (t%mass(k) < light_mass) then
                    write (wl, '(3a,es9.2,a)') 'body ', trim(t%name(k)), ': mass', t%mass(k), &
                        ' kg, far below the vertebrae''s 0.376-0.526 kg: needs tiny steps, the run may crawl'// &
                        ' (check units)'
                    call add(wl)
                end if
                ev = eigenvalues3(t%inertia(:, :, k))
                if (ev(1) < small_inertia) then
                    write (wl, '(3a,es9.2,a)') 'body ', trim(t%name(k)), ': smallest principal inertia', ev(1), &
                        ' kg m2, far below the vertebrae''s 2.96E-04-7.96E-04: the run may crawl (check units)'
                    call add(wl)
                end if
                if (ev(3) > (ev(1) + ev(2))*(1 + 1.0e-9_wp)) then
                    write (w, '(3a,3es10.3,a)') 'body ', trim(t%name(k)), ': principal moments', ev, &
                        ' kg m2 violate the triangle inequality (the largest exceeds the sum of the others)'
                    call add(w)
                end if
            end do
            do f = 1, size(model%family)
                call model%family(f)%f%plausibility(t, warnings)
            end do
            do e = 1, size(model%applied)
                call check_point(model%tree, model%applied(e)%body, model%applied(e)%point, 'applied load', warnings)
            end do
        end associate
    contains
        subroutine add(text)
            character(len=*), intent(in) :: text
            call add_warning(warnings, text)
        end subroutine add

    end subroutine plausibility_warnings

    !> Eigenvalues of a symmetric 3x3 matrix, ascending (trigonometric method).
    pure function eigenvalues3(a) result(ev)
        real(wp), intent(in) :: a(3, 3)
        real(wp) :: ev(3), q, p1, p2, p, r, phi, b(3, 3)
        integer :: i
        p1 = a(1, 2)**2 + a(1, 3)**2 + a(2, 3)**2
        q = (a(1, 1) + a(2, 2) + a(3, 3))/3
        if (p1 <= tiny(1.0_wp)) then
            ev = [a(1, 1), a(2, 2), a(3, 3)]
        else
            p2 = (a(1, 1) - q)**2 + (a(2, 2) - q)**2 + (a(3, 3) - q)**2 + 2*p1
            p = sqrt(p2/6)
            b = a
            do i = 1, 3
                b(i, i) = b(i, i) - q
            end do
            b = b/p
            r = half*(b(1, 1)*(b(2, 2)*b(3, 3) - b(2, 3)*b(3, 2)) - b(1, 2)*(b(2, 1)*b(3, 3) - b(2, 3)*b(3, 1)) + &
                      b(1, 3)*(b(2, 1)*b(3, 2) - b(2, 2)*b(3, 1)))
            r = max(-1.0_wp, min(1.0_wp, r))
            phi = acos(r)/3
            ev(3) = q + 2*p*cos(phi)
            ev(1) = q + 2*p*cos(phi + 2*acos(-1.0_wp)/3)
            ev(2) = 3*q - ev(1) - ev(3)
        end if
        ev = sort3(ev)
    end function eigenvalues3

    pure function sort3(v) result(s)
        real(wp), intent(in) :: v(3)
        real(wp) :: s(3)
        s = v
        if (s(1) > s(2)) s([1, 2]) = s([2, 1])
        if (s(2) > s(3)) s([2, 3]) = s([3, 2])
        if (s(1) > s(2)) s([1, 2]) = s([2, 1])
    end function sort3

end module hn_plausibility
