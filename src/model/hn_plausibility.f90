!> Physical plausibility of a valid deck: warnings, not errors. Masses and
!! principal inertias far below the vertebral range (runs that crawl), inertia
!! that violates the triangle inequality of principal moments, attachment
!! points far outside their body, and element stiffness two orders of
!! magnitude or more away from the reference model's (reference/parameters.md).
module hn_plausibility
    use hn_kinds, only: wp, zero, half
    use hn_model, only: model_t
    use hn_line_elements, only: line_attach_t
    implicit none
    private

    public :: plausibility_warnings

    ! reference values of the head/neck model (reference/parameters.md)
    real(wp), parameter :: ref_disc_axial = 5.0e5_wp      !! N/m
    real(wp), parameter :: ref_disc_bending = 20.0_wp     !! N m/rad
    real(wp), parameter :: ref_ligament_2mm = 30.0_wp     !! N at 2 mm stretch
    real(wp), parameter :: ref_muscle_m1 = 3000.0_wp      !! N/m
    real(wp), parameter :: ref_muscle_m2 = 400.0_wp       !! N s/m
    real(wp), parameter :: ref_limit_c1 = 100.0_wp        !! N m s/rad per rad
    real(wp), parameter :: factor = 100.0_wp              !! "orders of magnitude"
    real(wp), parameter :: light_mass = 0.01_wp           !! kg: ~40x below the lightest vertebra (0.376 kg)
    real(wp), parameter :: small_inertia = 1.0e-6_wp      !! kg m^2: ~300x below the smallest vertebral moment

contains

    !> Warnings about the model, one line each.
    subroutine plausibility_warnings(model, warnings)
        type(model_t), intent(in) :: model                            !! the model as read from the deck
        character(len=160), allocatable, intent(out) :: warnings(:)   !! one line per doubtful value (none: size 0)
        integer :: k, e
        real(wp) :: ev(3), reach
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
            do e = 1, size(model%discs)
                call check_point(model%discs(e)%body_a, model%discs(e)%pa, 'disc '//model%discs(e)%name)
                call check_point(model%discs(e)%body_b, model%discs(e)%pb, 'disc '//model%discs(e)%name)
                associate (d => model%discs(e))
                    call check_range('disc '//trim(d%name)//' axial stiffness d1 A/h', d%d1*d%area/d%h, &
                                     ref_disc_axial, 'N/m')
                    call check_range('disc '//trim(d%name)//' bending stiffness d1 Iy/h', d%d1*d%iy/d%h, &
                                     ref_disc_bending, 'N m/rad')
                end associate
            end do
            call check_lines('ligament', model%ligaments)
            call check_lines('muscle', model%muscles)
            call check_lines('spring', model%springs)
            do e = 1, size(model%ligaments)
                associate (l => model%ligaments(e))
                    call check_range('ligament '//trim(l%name)//' tension at 2 mm stretch', &
                                     l%l1*2.0e-3_wp + l%l2*(2.0e-3_wp)**l%n, ref_ligament_2mm, 'N')
                end associate
            end do
            do e = 1, size(model%muscles)
                call check_range('muscle '//trim(model%muscles(e)%name)//' stiffness m1', model%muscles(e)%m1, &
                                 ref_muscle_m1, 'N/m')
                call check_range('muscle '//trim(model%muscles(e)%name)//' damping m2', model%muscles(e)%m2, &
                                 ref_muscle_m2, 'N s/m')
            end do
            do e = 1, size(model%applied)
                call check_point(model%applied(e)%body, model%applied(e)%point, 'applied load')
            end do
            do e = 1, size(model%limits)
                if (model%limits(e)%local > 3) call check_range('joint-limit damper on '// &
                    trim(t%name(model%limits(e)%body))//' ramp C1', model%limits(e)%c1, ref_limit_c1, 'N m s/rad/rad')
            end do
        end associate
    contains
        subroutine add(text)
            character(len=*), intent(in) :: text
            character(len=160), allocatable :: tmp(:)
            integer :: n
            n = size(warnings)
            allocate (tmp(n + 1))
            tmp(1:n) = warnings
            tmp(n + 1) = text
            call move_alloc(tmp, warnings)
        end subroutine add

        !> Both attachment points of every line element of a list.
        subroutine check_lines(kind, at)
            character(len=*), intent(in) :: kind
            class(line_attach_t), intent(in) :: at(:)
            integer :: i
            do i = 1, size(at)
                call check_point(at(i)%body_a, at(i)%point_a, kind//' '//at(i)%name)
                call check_point(at(i)%body_b, at(i)%point_b, kind//' '//at(i)%name)
            end do
        end subroutine check_lines

        !> A point farther from its body's mass centre than max(0.25 m, 5 radii of gyration).
        subroutine check_point(k, p, what)
            integer, intent(in) :: k
            real(wp), intent(in) :: p(3)
            character(len=*), intent(in) :: what
            if (k < 1) return
            reach = max(0.25_wp, 5*sqrt((model%tree%inertia(1, 1, k) + model%tree%inertia(2, 2, k) + &
                                         model%tree%inertia(3, 3, k))/(2*model%tree%mass(k))))
            if (norm2(p) > reach) then
                write (w, '(a,a,a,f7.3,a,f6.3,a)') trim(what), ': attachment on ', trim(model%tree%name(k)), &
                    norm2(p), ' m from its mass centre, far outside the body (more than ', reach, ' m)'
                call add(w)
            end if
        end subroutine check_point

        subroutine check_range(what, v, ref, units)
            character(len=*), intent(in) :: what, units
            real(wp), intent(in) :: v, ref
            if (v <= zero) return
            if (v > factor*ref .or. v < ref/factor) then
                write (w, '(2a,es10.3,3a,es9.2,a)') trim(what), ' = ', v, ' ', units, &
                    ' is two or more orders of magnitude from the reference model''s ', ref, ' (check units)'
                call add(w)
            end if
        end subroutine check_range
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
