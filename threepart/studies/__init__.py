"""Studies above the methods: the matching pad test (:mod:`threepart.studies.matching`)."""
