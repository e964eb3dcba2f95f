% The counter wants to be done.
done.
