!> Element geometry in the result file, for drawing and post-processing:
!! group /model/elements with one subgroup per element family that has a
!! table (ligaments, muscles, springs, discs: each family's `result_table`
!! binding), each holding the element names, the two bodies an element
!! joins and its two attachment points in those bodies' frames, and the
!! family's extra datasets (the discs' plate frames, area and thickness; the
!! muscles' via points). Every dataset carries a `units` attribute. Layout
!! in docs/output-format.md.
module hn_results_model
    use hn_model, only: model_t
    use hn_element_family, only: element_table_t
    use hn_h5, only: h5_file_t
    implicit none
    private

    public :: write_element_tables

contains

    !> Write /model/elements/GROUP of every family of `model` that has a
    !! table into the open result file (its group /model must exist).
    subroutine write_element_tables(h5, model)
        type(h5_file_t), intent(inout) :: h5  !! result file being written
        type(model_t), intent(in) :: model    !! model whose elements are described
        type(element_table_t) :: tab
        integer :: f
        call h5%group('/model/elements')
        do f = 1, size(model%family)
            tab = model%family(f)%f%result_table()
            if (len_trim(tab%group) > 0) call write_table(h5, '/model/elements/'//trim(tab%group), tab)
        end do
    end subroutine write_element_tables

    !> Group `path` with datasets name (ne), body (ne, 2), point (ne, 2, 3)
    !! as h5py shows them, and the family's extra datasets.
    subroutine write_table(h5, path, t)
        type(h5_file_t), intent(inout) :: h5           !! result file being written
        character(len=*), intent(in) :: path           !! group to create
        type(element_table_t), intent(in) :: t         !! the family's table
        integer :: ne, k
        ne = size(t%name)
        call h5%group(path)
        call h5%attr_string(path, 'description', trim(t%description))
        call h5%write_text(path//'/name', t%name)
        call h5%write_int(path//'/body', reshape(t%body, [2*ne]), [2, ne])
        call h5%attr_string(path//'/body', 'units', '1')
        call h5%attr_string(path//'/body', 'description', 'body numbers of ends a and b (0 = R, else /model order)')
        call h5%write_real(path//'/point', reshape(t%point, [6*ne]), [3, 2, ne])
        call h5%attr_string(path//'/point', 'units', 'm')
        call h5%attr_string(path//'/point', 'description', &
                            'attachment points a and b in their body frames from the mass centre (in R for body 0)')
        do k = 1, size(t%extra)
            associate (x => t%extra(k), dpath => path//'/'//trim(t%extra(k)%name))
                if (allocated(x%i)) then
                    call h5%write_int(dpath, x%i, x%shape)
                else
                    call h5%write_real(dpath, x%r, x%shape)
                end if
                call h5%attr_string(dpath, 'units', trim(x%units))
                if (len_trim(x%description) > 0) call h5%attr_string(dpath, 'description', trim(x%description))
            end associate
        end do
    end subroutine write_table

end module hn_results_model
