os.execute("touch /tmp/rgraph_hostile_pwned")
