!> Card images for the tests of card handlers: one card image from its
!! name and fields (`card`), and a reader holding a few images with their
!! cards (`deck_of`, no TITLE card first: the cards of one group).
module hn_test_cards
    use hn_deck_reader, only: deck_reader_t
    use hn_deck_state, only: card_t, group_cards
    use hn_element_cards, only: family_card_t
    implicit none
    private

    public :: card, deck_of

contains

    !> A card image: the name in columns 1-8, fields F1.. in columns 11-20, 21-30, ...
    pure function card(key, fields) result(s)
        character(len=*), intent(in) :: key         !! the card name
        character(len=*), intent(in) :: fields(:)   !! its fields F1, F2, ... (at most 10 characters each)
        character(len=80) :: s
        integer :: f
        s = key
        do f = 1, size(fields)
            s(1 + 10*f:10 + 10*f) = fields(f)
        end do
    end function card

    !> A reader holding the images, located as "cards line k", and their
    !! cards (no TITLE card first: the cards of one group); `more`: cards of
    !! families outside the registry.
    subroutine deck_of(images, rd, cs_cards, more)
        character(len=*), intent(in) :: images(:)                 !! the card images
        type(deck_reader_t), intent(out) :: rd                    !! the reader holding them
        type(card_t), allocatable, intent(out) :: cs_cards(:)     !! their cards
        type(family_card_t), intent(in), optional :: more(:)      !! cards of families the registry does not list
        integer :: k
        rd%top = 'cards'
        allocate (rd%lines(size(images)))
        do k = 1, size(images)
            rd%lines(k)%text = trim(images(k))
            rd%lines(k)%source = 'cards'
            rd%lines(k)%line = k
        end do
        rd%nlines = size(images)
        call group_cards(rd, cs_cards, title_first=.false., more=more)
    end subroutine deck_of

end module hn_test_cards
