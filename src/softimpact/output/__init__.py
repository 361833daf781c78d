"""Files out: the output contract of each command (:mod:`.bar`, :mod:`.beam`,
:mod:`.series`, :mod:`.calibration`), atomic writing
(:mod:`.files`), figures (:mod:`.plots`) and the HTML report (:mod:`.report`)."""
