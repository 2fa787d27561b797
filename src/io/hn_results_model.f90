!> Element geometry in the result file, for drawing and post-processing:
!! group /model/elements with one subgroup per element family (ligaments,
!! muscles, springs, discs), each holding the element names, the two bodies
!! an element joins and its two attachment points in those bodies' frames.
!! Discs add their plate frames, area and thickness. Every dataset carries
!! a `units` attribute. Layout in docs/output-format.md.
module hn_results_model
    use hn_kinds, only: wp
    use hn_model, only: model_t
    use hn_h5, only: h5_file_t
    use hn_line_elements, only: max_via
    implicit none
    private

    public :: write_element_tables

    integer, parameter :: name_len = 12

    !> One family's element table: names, bodies and attachment points.
    type :: element_table_t
        character(len=name_len), allocatable :: name(:)  !! (ne) element names
        integer, allocatable :: body(:, :)               !! (2, ne) bodies a, b (0 = R)
        real(wp), allocatable :: point(:, :, :)          !! (3, 2, ne) points a, b in body frames [m]
    end type element_table_t

contains

    !> Write /model/elements/{ligaments,muscles,springs,discs} of `model`
    !! into the open result file (its group /model must exist).
    subroutine write_element_tables(h5, model)
        type(h5_file_t), intent(inout) :: h5  !! result file being written
        type(model_t), intent(in) :: model    !! model whose elements are described
        type(element_table_t) :: lig, mus, spr, dsc
        real(wp), allocatable :: plate(:), area(:), thickness(:)
        integer :: e, n

        ! ==== The only place that reads components of the element types ====
        ! (line elements: name, body_a, body_b, point_a, point_b; discs the
        ! same with pa, pb and the plate data ra, rb, area, h.) Springs have
        ! no name in the deck: they are called SPRING1, SPRING2, ...
        n = size(model%ligaments)
        lig = element_table([character(len=name_len) :: (model%ligaments(e)%name, e=1, n)], &
                            [(model%ligaments(e)%body_a, model%ligaments(e)%body_b, e=1, n)], &
                            [(model%ligaments(e)%point_a, model%ligaments(e)%point_b, e=1, n)])
        n = size(model%muscles)
        mus = element_table([character(len=name_len) :: (model%muscles(e)%name, e=1, n)], &
                            [(model%muscles(e)%body_a, model%muscles(e)%body_b, e=1, n)], &
                            [(model%muscles(e)%point_a, model%muscles(e)%point_b, e=1, n)])
        n = size(model%springs)
        spr = element_table([character(len=name_len) :: (spring_name(e), e=1, n)], &
                            [(model%springs(e)%body_a, model%springs(e)%body_b, e=1, n)], &
                            [(model%springs(e)%point_a, model%springs(e)%point_b, e=1, n)])
        n = size(model%discs)
        dsc = element_table([character(len=name_len) :: (model%discs(e)%name, e=1, n)], &
                            [(model%discs(e)%body_a, model%discs(e)%body_b, e=1, n)], &
                            [(model%discs(e)%pa, model%discs(e)%pb, e=1, n)])
        plate = [(model%discs(e)%ra, model%discs(e)%rb, e=1, n)]
        area = [(model%discs(e)%area, e=1, n)]
        thickness = [(model%discs(e)%h, e=1, n)]
        ! ==== end of the element components ====

        call h5%group('/model/elements')
        call write_table(h5, '/model/elements/ligaments', lig, 'ligament: tension-only band from point a to b')
        call write_table(h5, '/model/elements/muscles', mus, 'muscle: tension-only path from point a through its via points to b')
        call write_table(h5, '/model/elements/springs', spr, 'linear spring-damper from point a to b')
        call write_table(h5, '/model/elements/discs', dsc, &
                         'disc: lower plate centre (a, on body a) and upper plate centre (b, on body b)')
        call write_via_points(h5, model)
        call h5%write_real('/model/elements/discs/plate_frame', plate, [3, 3, 2, n])
        call h5%attr_string('/model/elements/discs/plate_frame', 'units', '1')
        call h5%attr_string('/model/elements/discs/plate_frame', 'description', &
                            'plate frames (lower, upper) in their body frames: h5py [e, plate, j, i] is R_ij')
        call h5%write_real('/model/elements/discs/area', area, [n])
        call h5%attr_string('/model/elements/discs/area', 'units', 'm^2')
        call h5%write_real('/model/elements/discs/thickness', thickness, [n])
        call h5%attr_string('/model/elements/discs/thickness', 'units', 'm')
    end subroutine write_element_tables

    !> A table from flat lists: names, body pairs (a, b per element) and
    !! point pairs (xyz of a, then of b, per element).
    pure function element_table(name, body, point) result(t)
        character(len=*), intent(in) :: name(:)  !! (ne) names
        integer, intent(in) :: body(:)           !! (2 ne) bodies a, b of each element
        real(wp), intent(in) :: point(:)         !! (6 ne) points a, b of each element [m]
        type(element_table_t) :: t
        integer :: ne
        ne = size(name)
        allocate (t%name(ne))
        t%name = name
        t%body = reshape(body, [2, ne])
        t%point = reshape(point, [3, 2, ne])
    end function element_table

    !> The muscles' via points (VIA cards): via_count (ne), via_body
    !! (ne, max_via) and via_point (ne, max_via, 3) as h5py shows them; a
    !! muscle's path runs from point a through its first via_count via
    !! points to point b.
    subroutine write_via_points(h5, model)
        type(h5_file_t), intent(inout) :: h5  !! result file being written
        type(model_t), intent(in) :: model    !! model whose muscles are described
        character(len=*), parameter :: path = '/model/elements/muscles'
        integer :: e, n
        n = size(model%muscles)
        call h5%write_int(path//'/via_count', [(model%muscles(e)%nvia, e=1, n)], [n])
        call h5%attr_string(path//'/via_count', 'units', '1')
        call h5%attr_string(path//'/via_count', 'description', &
                            'via points of each muscle path, in order from point a to point b')
        call h5%write_int(path//'/via_body', [(model%muscles(e)%via_body, e=1, n)], [max_via, n])
        call h5%attr_string(path//'/via_body', 'units', '1')
        call h5%attr_string(path//'/via_body', 'description', &
                            'bodies of the via points (0 = R, else /model order; unused slots 0)')
        call h5%write_real(path//'/via_point', [(model%muscles(e)%via_point, e=1, n)], [3, max_via, n])
        call h5%attr_string(path//'/via_point', 'units', 'm')
        call h5%attr_string(path//'/via_point', 'description', &
                            'via points in their body frames from the mass centre (unused slots 0)')
    end subroutine write_via_points

    !> Group `path` with datasets name (ne), body (ne, 2), point (ne, 2, 3) as h5py shows them.
    subroutine write_table(h5, path, t, description)
        type(h5_file_t), intent(inout) :: h5           !! result file being written
        character(len=*), intent(in) :: path           !! group to create
        type(element_table_t), intent(in) :: t         !! the family's table
        character(len=*), intent(in) :: description    !! what an element of the family is
        integer :: ne
        ne = size(t%name)
        call h5%group(path)
        call h5%attr_string(path, 'description', description)
        call h5%write_text(path//'/name', t%name)
        call h5%write_int(path//'/body', t%body, [2, ne])
        call h5%attr_string(path//'/body', 'units', '1')
        call h5%attr_string(path//'/body', 'description', 'body numbers of ends a and b (0 = R, else /model order)')
        call h5%write_real(path//'/point', t%point, [3, 2, ne])
        call h5%attr_string(path//'/point', 'units', 'm')
        call h5%attr_string(path//'/point', 'description', &
                            'attachment points a and b in their body frames from the mass centre (in R for body 0)')
    end subroutine write_table

    !> Name of the e-th spring (springs are unnamed on the deck).
    pure function spring_name(e) result(s)
        integer, intent(in) :: e  !! spring number
        character(len=name_len) :: s
        write (s, '(a, i0)') 'SPRING', e
    end function spring_name

end module hn_results_model
