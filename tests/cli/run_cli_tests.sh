#!/usr/bin/env bash
set -u
echo "cli tests: placeholder"
