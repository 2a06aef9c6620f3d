local f = load("\27Lua\84\0 binary chunk")
assert(f, "binary chunks are refused")
