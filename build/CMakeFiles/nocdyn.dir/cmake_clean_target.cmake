file(REMOVE_RECURSE
  "libnocdyn.a"
)
