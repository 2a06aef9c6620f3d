require "..etc.passwd"
