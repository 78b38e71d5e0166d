"""NEEMs of one user: writing (``writer``), reading back (``query``), keeping or wiping
(``lifecycle``) and bulk import of chains files (``importing``)."""
